#!/usr/bin/env bash
# A Slurm job array that computes every run of a `granchain reproduce` figure (or group) and preset,
# the large preset's across-N columns by default, in SHARDS shards with one store per shard.
#
#   bash scripts/slurm-reproduce-array.sh                 submit all shards (creates shards/ for the logs)
#   bash scripts/slurm-reproduce-array.sh --array=7       resubmit shard 7 (one that exited 75, its
#                                                         walltime spent, or one killed by a node
#                                                         failure): it resumes where it stopped
#   ./build/granchain merge --into data/paper/paper.db shards/fig6-large-*.db
#   ./build/granchain reproduce --figure fig6 --preset large --db data/paper/paper.db --out OUT
#                                                         (and fig7, fig9: they share the runs; nothing is run again)
#
# FIGURE and PRESET (environment, default fig6 and large) choose the runs: task i runs share i/SHARDS
# of each sweep that `granchain reproduce --figure FIGURE --preset PRESET --print-sweeps` lists, in
# that order, into shards/FIGURE-PRESET-i.db, each sweep with the part of the job's walltime still left
# (--time-limit: a point starts only if it is predicted to end within it). Points that can save their
# state (every engine's) keep it in shards/states-FIGURE-PRESET-i
# (--checkpoint-dir): they start while time is left, are saved 5 minutes before the limit and go on
# in the resubmitted task. A sweep that leaves points
# does not stop the task: later sweeps may hold points that still fit. A sweep whose longest point
# that keeps no state (its cost-model estimate with the sweep's margin of 1.25, from a dry run of the task's share)
# does not fit in what is left of the walltime waits for the resubmitted task, which starts with all
# of it; one that does not fit in the whole walltime is an error (exit 2: give the job a longer
# --time and WALLTIME_S). The task exits with the first failure's code (2, 3: a run turned
# unphysical, 4: the store failed), else 75 when any sweep left points (resubmit it), else 0.
# Run from the repository root. Outside a job the script submits itself with sbatch (extra arguments
# go to sbatch); the number of shards is fixed here, not read from the array, so that a resubmitted
# single task still runs share i of SHARDS.
#SBATCH --job-name=granchain-reproduce
#SBATCH --array=1-64
#SBATCH --cpus-per-task=8
#SBATCH --time=1-00:00:00
#SBATCH --output=shards/reproduce-%A-%a.log
set -euo pipefail
SHARDS=64
# The job's --time less half an hour for the store and the log (change both together). A day: every
# point of the large preset keeps its state, so none needs to fit in one job (its longest, N = 1000,
# e = 0.99, k = 1e10 on the exact engine, is predicted at 11.5 hours, and the cost model has missed by
# up to 4.7 times at N = 1000).
WALLTIME_S=$((24 * 3600 - 1800))
GRANCHAIN=${GRANCHAIN:-./build/granchain}
FIGURE=${FIGURE:-fig6}
PRESET=${PRESET:-large}

# Inside a job Slurm runs a copy of this script from its spool: the helper is found from the
# submission folder, the repository root.
# shellcheck source=scripts/slurm-array-task.sh
source "${SLURM_SUBMIT_DIR:-$(dirname "$0")/..}/scripts/slurm-array-task.sh"
i=$TASK
deadline=$((SECONDS + WALLTIME_S))
sweeps=$("$GRANCHAIN" reproduce --figure "$FIGURE" --preset "$PRESET" --print-sweeps | grep '^granchain sweep ' || true)
if [ -z "$sweeps" ]; then
  echo "slurm-reproduce-array: --figure $FIGURE --preset $PRESET lists no sweeps" >&2
  exit 2
fi
status=0
left=0
while read -r line; do
  remaining=$((deadline - SECONDS))
  if [ "$remaining" -lt 1 ]; then
    left=1
    break
  fi
  read -ra words <<< "${line#granchain }"
  store="shards/$FIGURE-$PRESET-$i.db"
  # Points of an engine that can save its state keep it in the task's folder of states, so that one
  # of them may run over several jobs; a sweep without such points refuses the folder (exit 2).
  states=(--checkpoint-dir "shards/states-$FIGURE-$PRESET-$i")
  "$GRANCHAIN" "${words[@]}" --shard "$i/$SHARDS" --db "$store" "${states[@]}" --dry-run > /dev/null 2>&1 || states=()
  # The longest point of this share still to run that keeps no state, with the sweep's margin, as
  # the sweep's own check counts it: a sweep refuses a time limit that it cannot hold.
  need=$("$GRANCHAIN" "${words[@]}" --shard "$i/$SHARDS" --db "$store" "${states[@]}" --dry-run |
    awk '/driven_column/ && !/\((stored|checkpointed)/ { v = $2 + 0; if (v > m) m = v } END { printf "%d", 1.25 * m + 1 }')
  if [ "$need" -gt "$WALLTIME_S" ]; then
    echo "slurm-reproduce-array: ${line}: its longest point needs ${need} s, more than the job's ${WALLTIME_S} s" >&2
    [ "$status" -eq 0 ] && status=2
    continue
  fi
  if [ "$need" -gt "$remaining" ]; then
    left=1  # the resubmitted task, with the whole walltime, runs it
    continue
  fi
  rc=0
  "$GRANCHAIN" "${words[@]}" --shard "$i/$SHARDS" --threads "${SLURM_CPUS_PER_TASK:-1}" --db "$store" "${states[@]}" \
      --time-limit "${remaining}s" --progress -q || rc=$?
  if [ "$rc" -eq 75 ]; then
    left=1
  elif [ "$rc" -ne 0 ] && [ "$status" -eq 0 ]; then
    status=$rc
  fi
done <<< "$sweeps"
if [ "$status" -ne 0 ]; then
  exit "$status"
fi
if [ "$left" -eq 1 ]; then
  exit 75
fi
exit 0
