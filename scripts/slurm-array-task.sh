# Sourced by the Slurm job-array scripts (slurm-sweep-array.sh, slurm-reproduce-array.sh) after they
# set SHARDS: outside a job it creates shards/ (Slurm opens the #SBATCH --output log before the job
# starts, so the folder must exist) and submits the calling script with sbatch, passing the script's
# arguments on to sbatch; inside task i of the array it checks 1 <= i <= SHARDS and sets TASK = i.
# The number of shards is the script's, not the array's, so that a resubmitted single task still
# runs share i of SHARDS.
if [ -z "${SLURM_JOB_ID:-}" ]; then
  mkdir -p shards
  exec sbatch "$@" "$0"
fi
TASK=${SLURM_ARRAY_TASK_ID:?not a job array task (SLURM_ARRAY_TASK_ID is unset)}
if ! [[ "$TASK" =~ ^[0-9]+$ ]] || [ "$TASK" -lt 1 ] || [ "$TASK" -gt "$SHARDS" ]; then
  echo "$(basename "$0" .sh): array task $TASK is outside 1..$SHARDS (submit with --array=1-$SHARDS)" >&2
  exit 2
fi
mkdir -p shards
