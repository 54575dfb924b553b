#!/usr/bin/env bash
# Renders a scene on a Slurm cluster: a job array renders disjoint passes of
# every pixel's samples (or the frames of an animation), a job that depends
# on it merges the passes. docs/farm.md tells the whole story.
#
#   deploy/slurm/render-array.sh [options] SCENE OUT_DIR
#     --spp S          samples per pixel of the image (default: the scene's)
#     --passes N       split each image into N passes, one array task each (default 4)
#     --frames A..B    an animation instead: one array task per frame
#     --image NAME     the merged image's file name in OUT_DIR (default image.png)
#     --ptsc PATH      the ptsc binary on the nodes (default: ptsc on PATH)
#     --sbatch "ARGS"  more sbatch options (partition, time, account, …)
#     -- ARGS          more `ptsc render` options (--resolution, --seed, …)
#
# Every node must see SCENE, its includes and data files, and OUT_DIR at the
# same paths (a shared file system). Each task runs with --resume: a task
# that Slurm requeues (preemption, a node failure) or that stopped at its
# time limit (Slurm sends SIGTERM; ptsc saves its state) continues where it
# stopped. Prints the job ids; the merged image is OUT_DIR/NAME.
set -euo pipefail

spp="" passes=4 frames="" image="image.png" ptsc="ptsc" sbatch_extra="" render_extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --spp) spp=$2; shift 2 ;;
    --passes) passes=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --image) image=$2; shift 2 ;;
    --ptsc) ptsc=$2; shift 2 ;;
    --sbatch) sbatch_extra=$2; shift 2 ;;
    --) shift; render_extra=("$@"); break ;;
    -h|--help) sed -n 2,21p "$0"; exit 0 ;;
    -*) echo "render-array.sh: unknown option $1" >&2; exit 2 ;;
    *) break ;;
  esac
done
[ $# -ge 2 ] || { sed -n 2,21p "$0" >&2; exit 2; }
scene=$(realpath "$1") out=$(realpath -m "$2")
shift 2
[ "${1:-}" != "--" ] || shift
[ $# -eq 0 ] || render_extra+=("$@")
mkdir -p "$out/logs"
spp_args=()
[ -z "$spp" ] || spp_args=(--spp "$spp")
# Shell-quoted words (a trailing space after each), and one path (none).
q() { printf '%q ' "$@"; }
qp() { printf '%q' "$1"; }

if [ -n "$frames" ]; then
  first=${frames%..*} last=${frames#*..}
  # One task per frame; the task id is the frame's number.
  task="$(q "$ptsc" render "$scene" "${spp_args[@]}" --frames "$frames" "${render_extra[@]}") --frame \$SLURM_ARRAY_TASK_ID -o $(qp "$out/frame_######.png") --resume --checkpoint 300"
  array="$first-$last"
else
  task="$(q "$ptsc" render "$scene" "${spp_args[@]}" "${render_extra[@]}") --pass \$SLURM_ARRAY_TASK_ID/$passes -o $(qp "$out")/part_\$SLURM_ARRAY_TASK_ID.exr --resume --checkpoint 300"
  array="1-$passes"
fi

# shellcheck disable=SC2086
render_job=$(sbatch --parsable --job-name=ptsc-render --array="$array" \
  --requeue --signal=B:TERM@120 --output="$out/logs/render_%A_%a.log" $sbatch_extra \
  --wrap="exec $task")
echo "render job $render_job (array $array)"

if [ -z "$frames" ]; then
  # A failed pass cancels the merge (rather than leaving it pending).
  # shellcheck disable=SC2086
  merge_job=$(sbatch --parsable --job-name=ptsc-merge --dependency="afterok:$render_job" --kill-on-invalid-dep=yes \
    --output="$out/logs/merge_%j.log" $sbatch_extra \
    --wrap="exec $(q "$ptsc" merge)$(qp "$out")/part_*.exr -o $(qp "$out/$image")")
  echo "merge job $merge_job → $out/$image"
fi
