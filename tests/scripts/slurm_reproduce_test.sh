#!/usr/bin/env bash
# scripts/slurm-reproduce-array.sh with Slurm and granchain faked: outside a job it creates shards/
# and submits itself; inside task i it runs share i/64 of every sweep that reproduce --print-sweeps
# lists, each with the walltime left, goes on after a sweep that left points (exit 75) and exits
# 75, and exits with a failure's code before 75; the points that can save their state keep it in the
# task's folder of states and need not fit the walltime; a task outside 1..64 is refused. Then the real
# binary: every sweep of the large preset's across-N figures, as the script runs it, is accepted
# (a dry run of shard 1/64), and the 64 shards of one of them list each of its points exactly once.
set -euo pipefail
# shellcheck source=tests/scripts/fake_slurm.sh
source "$(dirname "$0")/fake_slurm.sh"
script="$repo/scripts/slurm-reproduce-array.sh"
# The job's walltime less half an hour, as the script states it (WALLTIME_S) and as #SBATCH --time.
walltime=$(( $(sed -n 's/^WALLTIME_S=\$((\(.*\)))$/\1/p' "$script") ))
sbatch_days=$(sed -n 's/^#SBATCH --time=\([0-9]*\)-00:00:00$/\1/p' "$script")
[ "$walltime" -eq $(( sbatch_days * 86400 - 1800 )) ] || fail "WALLTIME_S = $walltime s is not #SBATCH --time ($sbatch_days days) less half an hour"
cat > bin/granchain <<'STUB'
#!/usr/bin/env bash
if [ "$1" = reproduce ]; then
  echo "reproduce $*" > reproduce.args
  printf '%s\n' "# 96 points, predicted 1 CPU-hours" "granchain sweep --N 200 --e 0.975,0.3 --engine hard --start-k 1e12 --T 1e3 --T0 1" \
    "# 264 points" "granchain sweep --N 300 --e 0.1 --engine reference --k 1e5:1e10:x10 --T 1e3 --T0 1 --replicas 4" "# 360 distinct points"
  exit 0
fi
keeps=1
[[ " $* " == *" --start-k "* ]] && keeps=0
if [[ " $* " == *" --checkpoint-dir "* && $keeps -eq 0 ]]; then  # a sweep whose points keep no state (the fake's --start-k)
  echo "granchain: error: --checkpoint-dir = x: no point of this sweep can save its state" >&2
  exit 2
fi
if [[ " $* " == *" --dry-run "* ]]; then  # one point of this share, at FAKE_COST (no state) or FAKE_REF_COST seconds
  if [ "$keeps" -eq 1 ]; then
    echo "     1  ${FAKE_REF_COST:-100}  0  1  driven_column engine=reference N=300$([[ " $* " == *" --checkpoint-dir "* ]] && echo "  (checkpointed)")"
  else
    echo "     1  ${FAKE_COST:-100}  0  1  driven_column engine=hard N=200"
  fi
  exit 0
fi
echo "$*" >> sweeps.args
n=$(wc -l < sweeps.args)
codes=(${FAKE_CODES:-0 0})
exit "${codes[$((n - 1))]}"
STUB
chmod +x bin/granchain
task() {  # task 7 of the array with the fake binary; prints its exit code
  rm -f sweeps.args
  local rc=0
  SLURM_JOB_ID=1 SLURM_ARRAY_TASK_ID=7 SLURM_CPUS_PER_TASK=4 GRANCHAIN="$work/bin/granchain" FAKE_CODES="$1" bash "$script" || rc=$?
  echo "$rc"
}

# Submission: shards/ exists before sbatch runs; the extra arguments reach sbatch.
env -u SLURM_JOB_ID PATH="$work/bin:$PATH" bash "$script" --array=7
[ -d shards ] || fail "shards/ was not created before submission"
grep -q -- "--array=7 .*slurm-reproduce-array.sh" sbatch.args || fail "sbatch got: $(cat sbatch.args)"

# Task 7: both sweeps, share 7/64, the task's store, a time limit within the job's walltime.
[ "$(task "0 0")" -eq 0 ] || fail "task 7 did not succeed"
grep -q -- "--figure fig6 --preset large --print-sweeps" reproduce.args || fail "reproduce got: $(cat reproduce.args)"
[ "$(wc -l < sweeps.args)" -eq 2 ] || fail "task 7 ran $(wc -l < sweeps.args) sweeps, not 2"
head -1 sweeps.args | grep -q -- "^sweep --N 200 --e 0.975,0.3 --engine hard --start-k 1e12 --T 1e3 --T0 1 --shard 7/64 --threads 4 --db shards/fig6-large-7.db --time-limit [0-9]*s --progress -q$" ||
  fail "first sweep: $(head -1 sweeps.args)"
tail -1 sweeps.args | grep -q -- "--replicas 4 --shard 7/64 --threads 4 --db shards/fig6-large-7.db --checkpoint-dir shards/states-fig6-large-7 --time-limit" ||
  fail "second sweep (its points keep their states): $(tail -1 sweeps.args)"
limit=$(head -1 sweeps.args | sed 's/.*--time-limit \([0-9]*\)s.*/\1/')
[ "$limit" -gt $(( walltime - 1000 )) ] && [ "$limit" -le "$walltime" ] || fail "time limit $limit s, not the job's walltime less half an hour ($walltime s)"
# A share whose longest point cannot fit in the whole walltime is refused, and nothing of it runs
# (the next sweep does).
rm -f sweeps.args
rc=0
SLURM_JOB_ID=1 SLURM_ARRAY_TASK_ID=7 GRANCHAIN="$work/bin/granchain" FAKE_COST=$(( walltime * 4 / 5 )) bash "$script" 2> err.txt || rc=$?
[ "$rc" -eq 2 ] || fail "a share longer than the walltime exited $rc, not 2"
[ "$(wc -l < sweeps.args)" -eq 1 ] && ! grep -q -- "--N 200" sweeps.args ||
  fail "a share longer than the walltime ran (or the next sweep did not): $(cat sweeps.args)"
grep -q "its longest point needs $(( walltime + 1 )) s, more than the job's $walltime s" err.txt || fail "refusal: $(cat err.txt)"
# Points that keep their state may be longer than the walltime: they go on in the resubmitted task.
rm -f sweeps.args
SLURM_JOB_ID=1 SLURM_ARRAY_TASK_ID=7 GRANCHAIN="$work/bin/granchain" FAKE_REF_COST=$(( walltime * 4 )) FAKE_CODES="0 75" bash "$script" 2> err.txt || rc=$?
[ "$rc" -eq 75 ] || fail "a share with checkpointed points longer than the walltime exited $rc, not 75"
[ "$(wc -l < sweeps.args)" -eq 2 ] || fail "the checkpointed sweep did not run: $(cat sweeps.args)"
rc=0
# A sweep that left points: the next one still runs, and the task asks to be resubmitted.
[ "$(task "75 0")" -eq 75 ] || fail "a sweep that left points did not make the task exit 75"
[ "$(wc -l < sweeps.args)" -eq 2 ] || fail "the sweep after one that left points did not run"
# A failure's code comes before 75.
[ "$(task "75 3")" -eq 3 ] || fail "an unphysical run's exit 3 was hidden"
# Inside a real job Slurm runs a copy of the script from its spool folder: the helper it sources is
# found from the submission folder.
mkdir -p spool && cp "$script" spool/slurm_script
rm -f sweeps.args
SLURM_JOB_ID=1 SLURM_ARRAY_TASK_ID=7 SLURM_SUBMIT_DIR="$repo" GRANCHAIN="$work/bin/granchain" bash spool/slurm_script ||
  fail "the spooled copy failed"
[ "$(wc -l < sweeps.args)" -eq 2 ] || fail "the spooled copy ran $(wc -l < sweeps.args) sweeps"
# A task outside the array's range.
if SLURM_JOB_ID=1 SLURM_ARRAY_TASK_ID=65 GRANCHAIN="$work/bin/granchain" bash "$script" 2> err.txt; then
  fail "task 65 was accepted"
fi
grep -q "outside 1..64" err.txt || fail "task 65: $(cat err.txt)"

# The real binary: every sweep of the large preset, with the flags the script adds, is accepted, every
# point keeps its state (so none needs to fit in one job), and no two sweeps share a point (each is
# split into shards of its own: a shared point would be computed twice).
"$binary" reproduce --figure fig6 --preset large --print-sweeps > print.txt
grep '^granchain sweep ' print.txt > large.txt
[ "$(wc -l < large.txt)" -ge 10 ] || fail "the large preset lists $(wc -l < large.txt) sweeps"
: > keys.txt
while read -r line; do
  read -ra words <<< "${line#granchain }"
  "$binary" "${words[@]}" --shard 1/64 --threads 1 --db "$work/none.db" --checkpoint-dir "$work/states" --time-limit "${walltime}s" \
    --dry-run > /dev/null || fail "refused: $line"
  "$binary" "${words[@]}" --db "$work/none.db" --checkpoint-dir "$work/states" --dry-run > dry.txt
  awk '/driven_column/ && !/\(checkpointed\)/ { bad = 1 } END { exit bad }' dry.txt || fail "a point of '$line' keeps no state"
  awk '/driven_column/ { print $4 }' dry.txt >> keys.txt
done < large.txt
distinct=$(grep -o '^# [0-9]* distinct points' print.txt | awk '{ print $2 }')
[ "$(wc -l < keys.txt)" -eq "$distinct" ] || fail "the sweeps list $(wc -l < keys.txt) points, the preset $distinct distinct ones"
[ "$(sort -u keys.txt | wc -l)" -eq "$distinct" ] || fail "two sweeps share a point"
# The 64 shards of the N = 1000 replicas' sweep list each of its points once.
read -ra words <<< "$(grep -- '--N 1000 .*--replicas' large.txt | sed 's/^granchain //')"
"$binary" "${words[@]}" --db "$work/none.db" --dry-run | awk '/driven_column/ {print $4}' | sort > all.txt
: > shards.txt
for i in $(seq 1 64); do "$binary" "${words[@]}" --db "$work/none.db" --dry-run --shard "$i/64" | awk '/driven_column/ {print $4}' >> shards.txt; done
sort shards.txt > shards_sorted.txt
[ "$(wc -l < all.txt)" -gt 100 ] || fail "the N = 1000 sweep has $(wc -l < all.txt) points"
cmp -s all.txt shards_sorted.txt || fail "the shards do not partition the N = 1000 sweep"
echo "slurm reproduce array script: submission, shards, time limits, exit codes and the large preset's sweeps OK"
