#!/usr/bin/env bash
# The farm end to end on a one-node Slurm cluster started here: a job array
# of N passes of a bench scene, the dependent merge, and the same image
# rendered by one process; the two PNGs must be identical. Needs root,
# slurm-wlm and munge (see local-cluster.sh) and a release build.
#
#   deploy/slurm/try-local.sh [SCENE] [SPP] [N] [RESOLUTION]
#   (default: examples/bench/cornell.pts 64 4 128x128)
set -euo pipefail
cd "$(dirname "$0")/../.."
scene=${1:-examples/bench/cornell.pts} spp=${2:-64} n=${3:-4} resolution=${4:-128x128}
ptsc="$PWD/target/release/ptsc"
[ -x "$ptsc" ] || cargo build --release
out=$(mktemp -d /tmp/ptsc-farm.XXXXXX)
eval "$(deploy/slurm/local-cluster.sh start)"
trap 'deploy/slurm/local-cluster.sh stop' EXIT
echo "== cluster"
sinfo
echo "== submit"
deploy/slurm/render-array.sh --ptsc "$ptsc" --spp "$spp" --passes "$n" "$scene" "$out" -- --resolution "$resolution" | tee "$out/jobs.txt"
merge_job=$(awk '/^merge job/ { print $3 }' "$out/jobs.txt")
t0=$(date +%s)
# Until the merge leaves the queue (done, or cancelled by a failed pass).
for _ in $(seq 600); do
  squeue -h -j "$merge_job" 2>/dev/null | grep -q . || break
  sleep 1
done
echo "== jobs done in $(( $(date +%s) - t0 )) s"
scontrol show job "$merge_job" 2>/dev/null | grep -o 'JobState=[A-Z]*' || true
for log in "$out"/logs/*.log; do echo "-- $(basename "$log")"; cat "$log"; done
echo "== one process"
"$ptsc" render "$scene" --spp "$spp" --resolution "$resolution" -o "$out/single.png"
if cmp "$out/image.png" "$out/single.png"; then
  echo "== the merged image of $n passes equals the single render ($out/image.png)"
else
  echo "== the merged image differs from the single render" >&2
  exit 1
fi
