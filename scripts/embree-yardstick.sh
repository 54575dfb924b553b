#!/usr/bin/env bash
# Embree as a yardstick (issue 39, item 4): traces the same ray sets through
# ptsc's BVH and through Embree 3, one thread, closest-hit and any-hit,
# coherent (camera) and incoherent (diffuse bounces from the camera's hits;
# random rays in the bounds of the blob or of the spheres) rays, on the
# bench scenes mesh (1M triangles) and spheres (10k spheres). Prints Embree's kernels, then
# Mrays/s, the agreement of the answers, build times and memory as Markdown
# tables (docs/performance.md, "Embree as a yardstick"). The halves:
# examples/embree_yardstick/ (ptsc: writes the geometry and rays, traces
# them, reports) and benches/embree/yardstick.c (Embree).
#
#   bash scripts/embree-yardstick.sh [SCENE...]      (default: mesh spheres)
#
# Needs Embree 3's headers and library (`apt-get install libembree-dev`,
# Debian's 3.13) and a C compiler; not run by CI. Environment:
#   RUNS       timed passes over each ray set, the median kept (default 5)
#   ROUNDS     rounds of ptsc then Embree, each cell the median over the
#              rounds (default 1; on a shared machine 3 evens out drift)
#   QUALITIES  Embree builds (default "high medium high-user": build
#              qualities; -user: spheres as user geometry with ptsc's test,
#              on scenes with spheres only)
#   OUT        where the rays and answers go (default a temporary folder,
#              removed after)
#   NICE       prefix of every timed command, e.g. "nice -n 19" on a machine
#              shared with someone timing (all sides alike)
#   JOBS       cargo's -j; CARGO_TARGET_DIR as cargo's
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
RUNS=${RUNS:-5} ROUNDS=${ROUNDS:-1} QUALITIES=${QUALITIES:-high medium high-user} NICE=${NICE:-}
TARGET=${CARGO_TARGET_DIR:-$ROOT/target}
[ $# -gt 0 ] || set -- mesh spheres
if [ -z "${OUT:-}" ]; then
  OUT=$(mktemp -d)
  trap 'rm -rf "$OUT"' EXIT
fi
mkdir -p "$OUT" "$TARGET/yardstick"

if [ ! -e /usr/include/embree3/rtcore.h ]; then
  echo "embree-yardstick: Embree 3 is missing (apt-get install libembree-dev)" >&2
  exit 2
fi
HARNESS=$TARGET/yardstick/yardstick
$NICE cc -std=c11 -O2 -Wall -Wextra -o "$HARNESS" "$ROOT/benches/embree/yardstick.c" -lembree3 -lm
$NICE cargo build --release --quiet --example embree_yardstick --manifest-path "$ROOT/Cargo.toml" \
  ${JOBS:+-j "$JOBS"}
YARDSTICK=$TARGET/release/examples/embree_yardstick

# Rounds: ptsc's half (writes the geometry and rays, traces and times them),
# then each Embree build on the same files.
rounds=()
for round in $(seq "$ROUNDS"); do
  dir=$OUT/round-$round
  rounds+=("$dir")
  YARDSTICK_RUNS=$RUNS $NICE "$YARDSTICK" dump "$dir" "$@"
  for s in "$@"; do
    for q in $QUALITIES; do
      # User-geometry spheres only where there are spheres.
      if [[ $q == *-user ]] && grep -q $'^count\tspheres\t0$' "$dir/$s/ptsc.tsv"; then
        continue
      fi
      if [ "$round" = 1 ]; then
        # Which builder, leaves and kernels Embree picks, and the exact
        # bytes of its tree (its verbose statistics; a build and one pass
        # of the camera rays, overwritten by the timed run below).
        YARDSTICK_EMBREE_CONFIG=verbose=2,threads=1 "$HARNESS" "$dir/$s" "$q" 1 camera 2>&1 \
          | grep -E '^building|^  total +: sah|^  intersector1 +=|^    intersector1 +=' \
          | sed 's/ \.\.\.$//; s/^ *//' | awk '!seen[$0]++' | sed "s|^|$s $q: |" >>"$OUT/kernels.txt"
      fi
      $NICE "$HARNESS" "$dir/$s" "$q" "$RUNS"
    done
  done
done

echo
echo "CPU: $(lscpu | sed -n 's/^Model name: *//p' | head -1); one thread; $RUNS timed passes per cell, $ROUNDS round(s)"
echo
echo "Embree's kernels for this CPU: $(YARDSTICK_EMBREE_CONFIG=verbose=1,threads=1 "$HARNESS" \
  "$OUT/round-1/$1" low 1 camera 2>&1 | sed -n 's/^ *Targets *: *//p' | head -1)"
rm -f "$OUT/round-1/$1/embree-low.tsv" "$OUT/round-1/$1"/*.embree-low.*
echo "Embree's choices (verbose=2):"
sed 's/^/    /' "$OUT/kernels.txt"
echo
"$YARDSTICK" report "${rounds[@]}"
