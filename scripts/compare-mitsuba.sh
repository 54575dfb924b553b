#!/usr/bin/env bash
# Side-by-side timing of ptsc and Mitsuba 3 on the benchmark scenes of
# ../shared/bench (SCENES.md): 512x512, 64 spp, max_depth 8, 2 threads, median
# of 3 runs each, the renderers taking turns run by run, waiting for an idle
# machine before every run.
#
#   bash scripts/compare-mitsuba.sh [SCENE...]        (default: cornell mesh spheres)
#
# Environment: RES SPP RUNS THREADS (as mitsuba.sh), VARIANTS (default
# "scalar_rgb llvm_ad_rgb"; llvm_ad_rgb needs libLLVM >= 17, e.g.
# `apt-get install libllvm19`).
# Both times are the render alone: Mitsuba's mi.render call, ptsc's render
# loop (scene loading, mesh reading and BVH build are reported apart as load).
# Prints one table: scene, ptsc median, Mitsuba medians and the ratios.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BENCH=${BENCH:-$ROOT/../shared/bench}
RES=${RES:-512} SPP=${SPP:-64} RUNS=${RUNS:-3} THREADS=${THREADS:-2}
export RES SPP RUNS THREADS
[ $# -gt 0 ] || set -- cornell mesh spheres
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

cargo build --release --quiet --manifest-path "$ROOT/Cargo.toml"
PTSC=$ROOT/target/release/ptsc

median() { sort -g | awk '{ a[NR] = $1 } END { print a[int((NR + 1) / 2)] }'; }

# Round by round, each scene: one ptsc run, then one run of each Mitsuba
# variant (RUNS=1 mitsuba.sh). A machine that slows down mid-way then slows
# both sides alike; timing all of ptsc first and Mitsuba after once put a
# drift on Mitsuba alone (session 6: its llvm_ad_rgb mesh runs went 4.98 ->
# 5.75-6.64 s and flattered ptsc's ratio 1.24 -> 1.12).
declare -A ptsc_runs ptsc_load mits_runs
for round in $(seq "$RUNS"); do
  for s in "$@"; do
    python3 "$BENCH/cpuload.py" wait >/dev/null 2>&1 || true
    line=$("$PTSC" render "$ROOT/examples/bench/$s.pts" --resolution "${RES}x${RES}" --spp "$SPP" \
             --threads "$THREADS" -o "$OUT/$s.exr" 2>&1 | tail -1)
    # "...: WxH, N spp in T s (P M paths/s, R M rays/s: ...; load L s; peak memory M MB) → OUT"
    t=$(sed -E 's/.* in ([0-9.]+) s .*/\1/' <<<"$line")
    ptsc_runs[$s]+="$t "
    ptsc_load[$s]=$(sed -E 's/.*load ([0-9.]+) s.*/\1/' <<<"$line")
    echo "[$s ptsc] round $round: $t s (load ${ptsc_load[$s]} s)" >&2
    # One run of each variant: "scene variant seconds paths_per_s".
    while read -r scene variant secs _; do
      [ "$scene" = "$s" ] || continue
      mits_runs[$s/$variant]+="$secs "
    done < <(RUNS=1 OUT="$OUT/mitsuba" bash "$BENCH/mitsuba.sh" bench "$s" | grep -v '^#')
  done
done

median_of() { tr ' ' '\n' <<<"$1" | grep . | median; }
declare -A ptsc_s
for s in "$@"; do
  ptsc_s[$s]=$(median_of "${ptsc_runs[$s]}")
  echo "ptsc $s: runs ${ptsc_runs[$s]}s, median ${ptsc_s[$s]} s (load ${ptsc_load[$s]} s)" >&2
  for v in scalar_rgb llvm_ad_rgb; do
    [ -n "${mits_runs[$s/$v]:-}" ] && echo "mitsuba $s $v: runs ${mits_runs[$s/$v]}s" >&2
  done
done
mits=$(for key in "${!mits_runs[@]}"; do
  echo "${key%/*} ${key#*/} $(median_of "${mits_runs[$key]}")"
done)

echo
echo "| scene | ptsc (s) | Mitsuba scalar_rgb (s) | Mitsuba llvm_ad_rgb (s) | ptsc / scalar | ptsc / llvm |"
echo "| --- | --- | --- | --- | --- | --- |"
for s in "$@"; do
  sc=$(awk -v s="$s" '$1 == s && $2 == "scalar_rgb" { print $3 }' <<<"$mits")
  ll=$(awk -v s="$s" '$1 == s && $2 == "llvm_ad_rgb" { print $3 }' <<<"$mits")
  ratio() { [ -n "$2" ] && awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }' || echo "-"; }
  echo "| $s | ${ptsc_s[$s]} | ${sc:--} | ${ll:--} | $(ratio "${ptsc_s[$s]}" "$sc") | $(ratio "${ptsc_s[$s]}" "$ll") |"
done
echo
echo "(${RES}x${RES}, $SPP spp, max_depth 8, $THREADS threads, medians of $RUNS; render time only; ratio < 1: ptsc faster)"
