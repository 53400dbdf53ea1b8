#!/usr/bin/env bash
# PM1 on a Slurm cluster: the runs of `hcm generate` split over a job array, then
# joined into the same OUT, S1 and S2 one machine writes, byte for byte.
#
#   sbatch --array=0-3 examples/slurm/generate.sh            # four shards, any order
#   sbatch --dependency=afterok:JOBID examples/slurm/generate.sh merge
#
# Each array task makes shard SLURM_ARRAY_TASK_ID of SLURM_ARRAY_TASK_COUNT (hcm reads
# both itself: no --shard needed) with the cores Slurm gave it (HCM_THREADS); the merge
# step reads the shards in order and writes pm1.csv, pm1.s1.csv and pm1.s2.csv.
#
# Without a cluster, the same commands run as separate processes:
#   for i in 0 1 2 3; do SLURM_ARRAY_TASK_ID=$i SLURM_ARRAY_TASK_COUNT=4 bash examples/slurm/generate.sh; done
#   SHARDS=4 bash examples/slurm/generate.sh merge
#SBATCH --job-name=hcm-pm1
#SBATCH --cpus-per-task=2
#SBATCH --time=01:00:00
set -euo pipefail

hcm="${HCM:-hcm}"
scenario="${SCENARIO:-scenarios/bouncing_ball.toml}"
runs="${RUNS:-1000}"
seed="${SEED:-1}"
out="${OUT:-pm1}"
export HCM_THREADS="${SLURM_CPUS_PER_TASK:-${HCM_THREADS:-}}"
[ -n "$HCM_THREADS" ] || unset HCM_THREADS

if [ "${1:-}" = "merge" ]; then
    shards="${SHARDS:-${SLURM_ARRAY_TASK_COUNT:?give SHARDS, the number of shards}}"
    files=()
    for ((i = 0; i < shards; i++)); do files+=("$out.shard-$i.csv"); done
    # The merge is not a shard: it must not read the array's task variables.
    env -u SLURM_ARRAY_TASK_ID -u SLURM_ARRAY_TASK_COUNT "$hcm" generate \
        --scenario "$scenario" --runs "$runs" --seed "$seed" --merge "${files[@]}" --out "$out.csv"
else
    task="${SLURM_ARRAY_TASK_ID:?run as a Slurm array task (sbatch --array=0-3)}"
    index=$((task - ${SLURM_ARRAY_TASK_MIN:-0}))
    "$hcm" generate --scenario "$scenario" --runs "$runs" --seed "$seed" --out "$out.shard-$index.csv"
fi
