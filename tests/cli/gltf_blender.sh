#!/usr/bin/env bash
# A Blender-style .glb (scripts/make_blender_glb.py: Y-up, camera, point lamp in candela, an
# emissive panel with KHR_materials_emissive_strength, a cube sampled every frame at 30 fps)
# renders without edits: `steadylight render scene.glb` picks 30 fps from the keys, the image is
# not black, the red cube moves from the left of the picture to the right, and nothing in it is
# warned about (its roughness 0.5 materials are rough plastics now, no longer ignored).
set -euo pipefail
binary=$1 source=$2 out=$3

rm -rf "$out"
mkdir -p "$out"
python3 "$source/scripts/make_blender_glb.py" "$out/blender.glb"
"$binary" info "$out/blender.glb" | tee "$out/info.txt"
grep -qF "frames: 25 at 30 fps (from the glTF keys, one every 1/30 s)" "$out/info.txt" \
  || { echo "expected 25 frames at 30 fps from the sampled keys"; exit 1; }
grep -q "Cube#0 *dynamic" "$out/info.txt" || { echo "the animated cube is not dynamic"; exit 1; }
grep -q "Light Panel .*emitter" "$out/info.txt" || { echo "the emissive panel is not a light"; exit 1; }
for frame in 1 24; do
  "$binary" render "$out/blender.glb" --method path --frames $frame --spp 4 --size 48x27 --out "$out/frames" \
    --no-progress 2>&1 | tee "$out/render_$frame.log"
done
stats="$source/tests/cli/png_stats.py"
mean=$(python3 "$stats" mean "$out/frames/blender_0001.png")
read -r left1 right1 < <(python3 "$stats" redness "$out/frames/blender_0001.png")
read -r left24 right24 < <(python3 "$stats" redness "$out/frames/blender_0024.png")
echo "mean code value of frame 1: $mean; redness left/right third: frame 1 $left1/$right1, frame 24 $left24/$right24"
python3 -c "import sys; sys.exit(not $mean > 20)" || { echo "frame 1 is (nearly) black"; exit 1; }
# The red cube slides from the left third (frame 1) to the right third (frame 24).
python3 -c "import sys; sys.exit(not ($left1 > $right1 + 5 and $right24 > $left24 + 5))" \
  || { echo "the cube did not move from left to right"; exit 1; }
count=$(grep -c "warning" "$out/render_1.log" || true)
[ "$count" -eq 0 ] || { echo "expected no warnings, got $count"; exit 1; }
echo "ok"
