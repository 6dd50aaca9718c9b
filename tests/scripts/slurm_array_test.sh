#!/usr/bin/env bash
# scripts/slurm-sweep-array.sh with Slurm faked: outside a job it creates shards/ and submits
# itself with the given sbatch arguments; inside task i of the array it runs share i/16, also when
# the task was resubmitted alone (SLURM_ARRAY_TASK_COUNT=1); a task outside 1..16 is refused; and
# the 16 shards' dry runs list every point of the grid exactly once.
set -euo pipefail
# shellcheck source=tests/scripts/fake_slurm.sh
source "$(dirname "$0")/fake_slurm.sh"
cat > bin/granchain <<'STUB'
#!/usr/bin/env bash
echo "$*" > granchain.args
STUB
chmod +x bin/granchain

# Submission: shards/ exists before sbatch runs; the extra arguments reach sbatch.
env -u SLURM_JOB_ID PATH="$work/bin:$PATH" bash "$repo/scripts/slurm-sweep-array.sh" --array=7
[ -d shards ] || fail "shards/ was not created before submission"
grep -q -- "--array=7 .*slurm-sweep-array.sh" sbatch.args || fail "sbatch got: $(cat sbatch.args)"

# Inside the job: task 7 of a full array, and task 7 resubmitted alone.
for count in 16 1; do
  SLURM_JOB_ID=1 SLURM_ARRAY_TASK_ID=7 SLURM_ARRAY_TASK_COUNT=$count SLURM_ARRAY_TASK_MAX=7 SLURM_CPUS_PER_TASK=4 \
    GRANCHAIN="$work/bin/granchain" bash "$repo/scripts/slurm-sweep-array.sh"
  grep -q -- "--shard 7/16 --threads 4 --db shards/fig5-7.db --time-limit 23.5h" granchain.args || fail "task 7 (count $count) ran: $(cat granchain.args)"
done
# A task outside the array's range.
if SLURM_JOB_ID=1 SLURM_ARRAY_TASK_ID=17 GRANCHAIN="$work/bin/granchain" bash "$repo/scripts/slurm-sweep-array.sh" 2> err.txt; then
  fail "task 17 was accepted"
fi
grep -q "outside 1..16" err.txt || fail "task 17: $(cat err.txt)"

# The 16 shards' points, as the real binary lists them, partition the grid.
grid=(sweep --N 25 --e 0.80:0.998:0.002 --k 1e5:1e10:x10 --T 1e4 --seed 1 --dry-run)
"$binary" "${grid[@]}" | awk '/driven_column/ {print $4}' | sort > all.txt
: > shards.txt
for i in $(seq 1 16); do "$binary" "${grid[@]}" --shard "$i/16" | awk '/driven_column/ {print $4}' >> shards.txt; done
sort shards.txt > shards_sorted.txt
[ "$(wc -l < all.txt)" -eq 600 ] || fail "the grid has $(wc -l < all.txt) points, not 600"
cmp -s all.txt shards_sorted.txt || fail "the shards do not partition the grid"
echo "slurm array script: submission, shard arithmetic and partition OK"
