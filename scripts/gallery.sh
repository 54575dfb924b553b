#!/usr/bin/env bash
# Renders the examples gallery (the paper's figures) into docs/gallery/*.png,
# the images the README shows. Each scene renders with its own settings except
# the sample count (SPP, default 64) and the size (at most 256 wide).
#
#   bash scripts/gallery.sh          # about a minute on 2 cores
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
SPP=${SPP:-64}
cargo build --release --quiet --manifest-path "$ROOT/Cargo.toml"
mkdir -p "$ROOT/docs/gallery"
for scene in cornell_colour_bleeding glass beer gloss dof motion mirror point_light checker image_map marble still_life studio metals plastic_and_glass outdoor many_lights dining_room forest column principled obj_materials gltf cutouts light_shafts; do
  # Media are noisier per sample: the hazy room gets 8 times the samples.
  spp=$SPP
  [ "$scene" = light_shafts ] && spp=$((SPP * 8))
  "$ROOT/target/release/ptsc" render "$ROOT/examples/$scene.pts" --spp "$spp" \
    -o "$ROOT/docs/gallery/$scene.png"
done
