#!/usr/bin/env bash
# Renders the truth suite's converged path-traced references (docs/truth-suite.md) with the
# project's own path tracer, at each scene's full size, as float EXRs in tests/references/:
#   <scene>_<frame:04>.exr            4096 samples per pixel: frame 0 and the middle frame
#   crn/<scene>_<frame:04>.exr        1024 samples, --fixed-seed (common random numbers): the
#                                     pairs (0,1), (n/4,n/4+1), (n/2,n/2+1), (3n/4,3n/4+1)
#   crn_seed1/<scene>_<frame:04>.exr  the middle pair again with --seed 1: the references' own
#                                     noise floor for the temporal-noise figure
# Resumable: references already there are kept, so it can run over several sittings. It takes
# hours on 2 cores (a 320x240 frame at 4096 samples is several minutes): run it in the
# background, e.g. `nohup bash scripts/make_references.sh table corridor &`.
#   bash scripts/make_references.sh [--still-only] [SCENE...]   (default: every suite scene)
set -euo pipefail
cd "$(dirname "$0")/.."
binary=${STEADYLIGHT:-build/steadylight}
still_only=0
if [ "${1:-}" = --still-only ]; then still_only=1; shift; fi
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(table corridor mirror_room glass_move flythrough switch_room ball cornell blender_room blender_textured blender_glass
  daylit_room daylit_sun outdoor_hdri torch_corridor daylit_sweep)
out=tests/references
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# render SCENE FRAME SPP SUBFOLDER [EXTRA OPTIONS...]: one reference, unless it exists.
render() {
  local scene=$1 frame=$2 spp=$3 folder=$4
  shift 4
  local name
  name=$(printf "%s_%04d.exr" "$scene" "$frame")
  mkdir -p "$out/$folder"
  [ -s "$out/$folder/$name" ] && return 0
  echo "$(date +%H:%M:%S) $folder/$name ($spp spp $*)"
  rm -rf "$work/frame"
  "$binary" render "scenes/$scene.json" --method path --frames "$frame" --spp "$spp" --exr-type float \
    --out "$work/frame" --quiet "$@"
  mv "$work/frame/$name" "$out/$folder/$name"
}

for scene in "${scenes[@]}"; do
  frames=$("$binary" info "scenes/$scene.json" | sed -n 's/^frames: \([0-9]*\) .*/\1/p')
  render "$scene" 0 4096 .
  [ "$frames" -gt 1 ] && render "$scene" $((frames / 2)) 4096 .
done
[ $still_only = 1 ] && exit 0
for scene in "${scenes[@]}"; do
  frames=$("$binary" info "scenes/$scene.json" | sed -n 's/^frames: \([0-9]*\) .*/\1/p')
  [ "$frames" -gt 1 ] || continue
  for first in 0 $((frames / 4)) $((frames / 2)) $((3 * frames / 4)); do
    for frame in $first $((first + 1)); do render "$scene" "$frame" 1024 crn --fixed-seed; done
  done
  for frame in $((frames / 2)) $((frames / 2 + 1)); do render "$scene" "$frame" 1024 crn_seed1 --fixed-seed --seed 1; done
done
