#!/usr/bin/env bash
# A/B timing of ptsc builds on one scene: the binaries take turns, run after
# run, so that drift in the machine's speed falls on all of them alike.
# Prints each binary's median and minimum render time (the "in T s" figure).
#
#   bash scripts/ab.sh SCENE SPP ROUNDS BIN...
#   e.g. cp target/release/ptsc /tmp/a; (change, build); cp target/release/ptsc /tmp/b
#        bash scripts/ab.sh examples/bench/mesh.pts 16 3 /tmp/a /tmp/b
#
# Environment: THREADS (default 2).
set -euo pipefail
[ $# -ge 4 ] || { sed -n 2,10p "$0"; exit 2; }
scene=$1 spp=$2 rounds=$3
shift 3
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
declare -A times
for _ in $(seq "$rounds"); do
  for bin in "$@"; do
    line=$("$bin" render "$scene" --spp "$spp" --threads "${THREADS:-2}" -o "$out/ab.exr" 2>&1 | tail -1)
    times[$bin]+="$(sed -E 's/.* in ([0-9.]+) s .*/\1/' <<<"$line") "
  done
done
for bin in "$@"; do
  tr ' ' '\n' <<<"${times[$bin]}" | grep . | sort -g |
    awk -v b="$bin" '{ a[NR] = $1 } END { printf "%s: median %s s, min %s s (%d runs)\n", b, a[int((NR + 1) / 2)], a[1], NR }'
done
