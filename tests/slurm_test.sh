#!/usr/bin/env bash
# Slurm for real (issue 21 item 2, the harness): scripts/slurm_local.sh starts a single-node cluster (munged,
# slurmctld, slurmd on localhost), a job array of shadetwin runs goes through sbatch --array, every task's result is
# checked, and the daemons are stopped. Usage: slurm_test.sh SHADETWIN SOURCE_DIR WORK_DIR
set -euo pipefail
bin=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
work=$(cd "$work" && pwd)
trap 'bash "$src/scripts/slurm_local.sh" stop "$work/cluster"' EXIT
eval "$(bash "$src/scripts/slurm_local.sh" start "$work/cluster")"
cat > "$work/array.sbatch" <<SB
#!/bin/bash
#SBATCH --array=0-2
#SBATCH --cpus-per-task=1
#SBATCH --output=$work/task_%a.out
exec "$bin" --threads 1 verify math --count 2000 --seed \$((SLURM_ARRAY_TASK_ID + 1)) --json "$work/task_\$SLURM_ARRAY_TASK_ID.json"
SB
job=$(sbatch --parsable --wait "$work/array.sbatch")
for t in 0 1 2; do
  grep -q '"passed": true' "$work/task_$t.json" || { echo "task $t: no passing report"; cat "$work/task_$t.out"; exit 1; }
done
echo "slurm: job $job, 3 array tasks of shadetwin verify math passed"
