#!/usr/bin/env bash
# A Slurm job array that runs one granchain sweep in SHARDS shards, one store per shard.
#
#   bash scripts/slurm-sweep-array.sh               submit all shards (creates shards/ for the logs)
#   bash scripts/slurm-sweep-array.sh --array=7     resubmit shard 7 (one that exited 75, having left
#                                                   points its walltime could not hold, or one killed
#                                                   by a node failure): it resumes where it stopped
#   ./build/granchain merge --into fig5.db shards/fig5-*.db     join the shards when all have finished
#
# Run from the repository root. Outside a job the script submits itself with sbatch (extra
# arguments go to sbatch); inside the job it runs its shard. The number of shards is fixed here,
# not read from the array, so that a resubmitted single task still runs share i of SHARDS.
#SBATCH --job-name=granchain-fig5
#SBATCH --array=1-16
#SBATCH --cpus-per-task=8
#SBATCH --time=24:00:00
#SBATCH --output=shards/fig5-%a.log
set -euo pipefail
SHARDS=16
GRANCHAIN=${GRANCHAIN:-./build/granchain}

# Inside a job Slurm runs a copy of this script from its spool: the helper is found from the
# submission folder, the repository root.
# shellcheck source=scripts/slurm-array-task.sh
source "${SLURM_SUBMIT_DIR:-$(dirname "$0")/..}/scripts/slurm-array-task.sh"
i=$TASK
# The paper's Fig. 4 grid for N = 25: e from 0.80 to 0.998, six values of k, T = 1e4. The time
# limit, half an hour inside the job's --time, starts only points predicted to end before the job is
# killed; a shard with points left exits 75 and is resubmitted with --array=i.
"$GRANCHAIN" sweep --N 25 --e 0.80:0.998:0.002 --k 1e5:1e10:x10 --T 1e4 --seed 1 \
    --shard "$i/$SHARDS" --threads "${SLURM_CPUS_PER_TASK:-1}" --db "shards/fig5-$i.db" --time-limit 23.5h --progress -q
