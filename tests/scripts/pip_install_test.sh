#!/usr/bin/env bash
# pip installs the Python package from the source tree, offline and without build isolation, into a
# fresh virtual environment (Debian's numpy seen through --system-site-packages); the package then
# imports without PYTHONPATH from any folder, gives the numbers of the build's module, and pip
# uninstalls it. The extension comes from the existing build folder (GRANCHAIN_BUILD_DIR), so the
# test checks the packaging, not a second compilation; `pip install .` alone configures and builds
# its own (docs/python.md).
set -euo pipefail
source_dir=$1
build=$2
venv=$(mktemp -d)
trap 'rm -rf "$venv"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
/usr/bin/python3 -m venv --system-site-packages "$venv" || fail "python3 -m venv (Debian: python3-venv)"
GRANCHAIN_BUILD_DIR="$build" "$venv/bin/pip" install --no-build-isolation --no-index -q "$source_dir" > "$venv/pip.log" 2>&1 \
  || { cat "$venv/pip.log"; fail "pip install"; }
cd /
installed=$(env -u PYTHONPATH "$venv/bin/python" -c "import granchain; print(granchain.__file__)") || fail "import granchain"
case "$installed" in "$venv"/*) ;; *) fail "granchain imported from $installed, not from the virtual environment" ;; esac
code='import granchain, warnings
warnings.simplefilter("ignore")
r = granchain.run(N=3, e=0.8, T=50, seed=5)
print(repr(r.n_coll), granchain.__version__)'
a=$(env -u PYTHONPATH "$venv/bin/python" -c "$code") || fail "run() in the installed package"
b=$(PYTHONPATH="$build/python" /usr/bin/python3 -c "$code") || fail "run() in the build's module"
[ "$a" = "$b" ] || fail "installed package gives '$a', the build's module '$b'"
"$venv/bin/pip" uninstall -y -q granchain > /dev/null || fail "pip uninstall"
if env -u PYTHONPATH "$venv/bin/python" -c "import granchain" 2> /dev/null; then fail "still importable after pip uninstall"; fi
echo "pip: installed into a virtual environment, imported without PYTHONPATH, same numbers, uninstalled"
