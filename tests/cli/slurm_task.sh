#!/bin/bash
# One task of a Slurm array job sliding a shot (tests/cli/slurm.sh; README "Farm" has the same
# submission): frames FIRST..LAST, FIRST = SLURM_ARRAY_TASK_ID, LAST = FIRST + the array's step
# - 1, but never past the shot's last frame, which is passed explicitly (SLURM_ARRAY_TASK_MAX is
# the last task's first frame, not the shot's last; skinslide would clamp an overshoot anyway).
# Slides the shot's point cache into OUT/pc2 (a chunk, OUT/pc2/shot.FIRST-LAST.pc2) and its OBJ
# sequence into OUT/obj.
# Usage: sbatch --array=1-24:10 slurm_task.sh OUT LAST_FRAME SHOT_DIR [SLOW_TASK]
#   SHOT_DIR holds bind.obj, patch.txt, shot.pc2 and frames/arm.NNNN.obj; SKINSLIDE names the
#   binary. SLOW_TASK: the task starting at that frame slides its cache with options that take
#   minutes a frame, so that a test can cancel it mid-run.
set -eu
# Checked inline: sbatch runs a copy of this script from its spool folder, away from require.sh.
[ $# -ge 3 ] || { echo "slurm_task.sh: cannot start: OUT LAST_FRAME SHOT_DIR expected" >&2; exit 2; }
[ -x "${SKINSLIDE:-}" ] || { echo "slurm_task.sh: cannot start: SKINSLIDE='${SKINSLIDE:-}' is not the skinslide binary" >&2; exit 2; }
[ -n "${SLURM_ARRAY_TASK_ID:-}" ] || { echo "slurm_task.sh: cannot start: SLURM_ARRAY_TASK_ID is not set (run it with sbatch --array)" >&2; exit 2; }
out=$1 end=$2 shot=$3 slow=${4:-}
first=$SLURM_ARRAY_TASK_ID
last=$((first + ${SLURM_ARRAY_TASK_STEP:-1} - 1))
[ "$last" -le "$end" ] || last=$end
extra=()
[ "$first" = "$slow" ] && extra=(--solver search --rotation-fits 1000 --max-iterations 100000 --tolerance 0)
"$SKINSLIDE" -q -j 1 "${extra[@]}" --frames "$first-$last" --patch "$shot/patch.txt" \
  -o "$out/pc2" "$shot/bind.obj" "$shot/shot.pc2"
"$SKINSLIDE" -q -j 1 --frames "$first-$last" --patch "$shot/patch.txt" \
  -o "$out/obj" "$shot/bind.obj" "$shot"/frames/*.obj
