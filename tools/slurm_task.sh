#!/bin/sh
# One task of a study's Slurm job array (-runner slurm: freefem_scripts/lib/wff_runner.idp):
#   sbatch --array=0-N ... tools/slurm_task.sh LIST
# runs line $SLURM_ARRAY_TASK_ID + 1 of the job list LIST (label, log, program, arguments:
# tab-separated fields, never split again) as the local runner runs a line, its output into
# the job's log, and writes its exit code to LIST.<task>.exit (tools/slurm_task.edp).
# Run from the repository root (sbatch runs it in the folder it was submitted from).
[ $# -eq 1 ] && [ -n "${SLURM_ARRAY_TASK_ID:-}" ] ||
    { echo "error: slurm_task: usage: sbatch --array=... tools/slurm_task.sh LIST (in a job array)"; exit 2; }
exec sh tools/ff.sh tools/slurm_task.edp "$1" "$SLURM_ARRAY_TASK_ID"
