#!/usr/bin/env bash
# Renders the converged path-traced references that the photon-mapping tests compare against:
# a frame of every truth-suite scene (docs/truth-suite.md) at 80x60, 4096 samples per pixel, into tests/scenes/golden/.
# Run after changing the path tracer or the scenes: bash scripts/make_golden.sh [BINARY [ENTRY...]]
# (ENTRY as below: only those; default every scene).
set -euo pipefail
cd "$(dirname "$0")/.."
binary=${1:-build/steadylight}
shift || true
out=tests/scenes/golden
# SCENE or SCENE:FRAME (a frame in a later segment).
entries=("$@")
[ ${#entries[@]} -gt 0 ] || entries=(cornell ball table corridor mirror_room flythrough glass_move switch_room:15 blender_room
  blender_textured blender_glass daylit_room daylit_sun outdoor_hdri torch_corridor:15 daylit_sweep:15)
for entry in "${entries[@]}"; do
  scene=${entry%%:*} frame=0
  [[ $entry == *:* ]] && frame=${entry#*:}
  "$binary" render "scenes/$scene.json" --method path --frames "$frame" --spp 4096 --size 80x60 --out "$out" --no-progress
  name=${scene}_$(printf %04d "$frame")
  rm -f "$out/$name.png" "$out/$name.manifest.json" "$out/$name.stats.json" "$out/$scene.settings.json"
done
