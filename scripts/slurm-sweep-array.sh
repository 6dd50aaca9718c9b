#!/usr/bin/env bash
# A Slurm job array that runs one granchain sweep in 16 shards, one store per shard; when all
# have finished, join them with:   ./build/granchain merge --into fig4.db shards/fig4-*.db
# Submit from the repository root:  sbatch scripts/slurm-sweep-array.sh
# A shard that is killed (time limit, node failure) is resumed by resubmitting its task:
#   sbatch --array=7 scripts/slurm-sweep-array.sh
#SBATCH --job-name=granchain-fig4
#SBATCH --array=1-16
#SBATCH --cpus-per-task=8
#SBATCH --time=24:00:00
#SBATCH --output=shards/fig4-%a.log
set -euo pipefail
mkdir -p shards
n=${SLURM_ARRAY_TASK_COUNT:-16}
i=${SLURM_ARRAY_TASK_ID:-1}
# The paper's Fig. 4 grid for N = 25: e from 0.80 to 0.998, six values of k, T = 1e4.
./build/granchain sweep --N 25 --e 0.80:0.998:0.002 --k 1e5:1e10:x10 --T 1e4 --seed 1 \
    --shard "$i/$n" --threads "${SLURM_CPUS_PER_TASK:-1}" --db "shards/fig4-$i.db" --progress -q
