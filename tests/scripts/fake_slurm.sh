# Sourced by the Slurm script tests: a scratch folder (removed on exit) as the working directory,
# bin/sbatch there faked to record its arguments in sbatch.args, fail() to end the test, and repo
# and binary (the real granchain, the test's first argument).
repo=$(cd "$(dirname "$0")/../.." && pwd)
binary=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
mkdir bin
cat > bin/sbatch <<'STUB'
#!/usr/bin/env bash
echo "sbatch $*" > sbatch.args
STUB
chmod +x bin/sbatch
fail() { echo "FAIL: $*" >&2; exit 1; }
