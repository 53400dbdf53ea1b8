#!/usr/bin/env bash
# An hcm job that splits on a Slurm cluster: `hcm generate` (PM1's runs) or `hcm power`
# (the diagnosis's power study) over a job array, then the shards joined into the same
# files one machine writes, byte for byte. The hcm command and its options follow the
# script's name; --shard, --merge and --out are the script's.
#
#   sbatch --array=0-3 examples/slurm/shards.sh generate --scenario scenarios/bouncing_ball.toml --runs 1000
#   sbatch --dependency=afterok:JOBID --export=ALL,SHARDS=4 \
#       examples/slurm/shards.sh merge generate --scenario scenarios/bouncing_ball.toml --runs 1000
#
#   sbatch --array=0-7 examples/slurm/shards.sh power --scenario my_rig.toml --seeds 20
#   sbatch --dependency=afterok:JOBID --export=ALL,SHARDS=8 \
#       examples/slurm/shards.sh merge power --scenario my_rig.toml --seeds 20
#
# Each array task makes shard SLURM_ARRAY_TASK_ID − SLURM_ARRAY_TASK_MIN of
# SLURM_ARRAY_TASK_COUNT (hcm reads the variables itself: no --shard needed) with the
# cores Slurm gave it (HCM_THREADS), to $OUT.shard-I.csv; the merge step reads the
# shards in order and writes $OUT.csv (and what the command writes beside it: S1 and S2,
# or the power table).
#
# Without a cluster, the same commands run as separate processes:
#   for i in 0 1 2 3; do SLURM_ARRAY_TASK_ID=$i SLURM_ARRAY_TASK_COUNT=4 bash examples/slurm/shards.sh generate --runs 1000 --scenario scenarios/bouncing_ball.toml; done
#   SHARDS=4 bash examples/slurm/shards.sh merge generate --runs 1000 --scenario scenarios/bouncing_ball.toml
#SBATCH --job-name=hcm-shards
#SBATCH --cpus-per-task=2
#SBATCH --time=01:00:00
set -euo pipefail

hcm="${HCM:-hcm}"
out="${OUT:-out}"
export HCM_THREADS="${SLURM_CPUS_PER_TASK:-${HCM_THREADS:-}}"
[ -n "$HCM_THREADS" ] || unset HCM_THREADS

if [ "${1:-}" = "merge" ]; then
    shift
    shards="${SHARDS:-${SLURM_ARRAY_TASK_COUNT:?give SHARDS, the number of shards}}"
    files=()
    for ((i = 0; i < shards; i++)); do files+=("$out.shard-$i.csv"); done
    # The merge is not a shard: it must not read the array's task variables.
    env -u SLURM_ARRAY_TASK_ID -u SLURM_ARRAY_TASK_COUNT "$hcm" "$@" \
        --merge "${files[@]}" --out "$out.csv"
else
    : "${1:?name the hcm command to split: generate or power}"
    task="${SLURM_ARRAY_TASK_ID:?run as a Slurm array task (sbatch --array=0-3)}"
    index=$((task - ${SLURM_ARRAY_TASK_MIN:-0}))
    "$hcm" "$@" --out "$out.shard-$index.csv"
fi
