#!/usr/bin/env bash
# Renders two small BALL frames with the path tracer and with the localized method (the
# default) and checks that exactly the expected files appear, whole; a second localized run
# must load the static cache the first one saved.
set -euo pipefail
binary=$1 source=$2 out=$3

expect_files() {  # expect_files DIR FILE...
  local dir=$1; shift
  for file in "$@"; do [ -s "$dir/$file" ] || { echo "missing $dir/$file"; exit 1; }; done
  [ "$(ls "$dir" | wc -l)" -eq $# ] || { echo "unexpected files in $dir:"; ls "$dir"; exit 1; }
}

rm -rf "$out"
"$binary" render "$source/scenes/ball.json" --method path --frames 3-4 --spp 1 --size 16x12 --out "$out/path" --no-progress
expect_files "$out/path" ball.settings.json ball_0003.exr ball_0003.png ball_0003.stats.json ball_0003.manifest.json \
  ball_0004.exr ball_0004.png ball_0004.stats.json ball_0004.manifest.json
grep -q '"camera_samples": 192' "$out/path/ball_0003.stats.json" || { echo "path stats lack 16x12x1 camera samples"; exit 1; }
"$binary" render "$source/scenes/ball.json" --method path --fixed-seed --frames 3 --spp 1 --size 16x12 --out "$out/fixed" --no-progress
grep -q '"fixed_seed": true' "$out/fixed/ball.settings.json" || { echo "--fixed-seed is not in the settings file"; exit 1; }
"$binary" render "$source/scenes/ball.json" --method path --transparent-background --frames 3 --spp 1 --size 16x12 --out "$out/clear" --no-progress
grep -q '"transparent_background": true' "$out/clear/ball.settings.json" || { echo "--transparent-background is not in the settings file"; exit 1; }

small=(--frames 3-4 --spp 1 --size 16x12 --photons 5000 --caustic-photons 0 --gather-samples 32 --no-progress)
"$binary" render "$source/scenes/ball.json" "${small[@]}" --out "$out/localized"
expect_files "$out/localized" ball.irrcache ball.settings.json ball_0003.exr ball_0003.png ball_0003.stats.json \
  ball_0003.manifest.json ball_0004.exr ball_0004.png ball_0004.stats.json ball_0004.manifest.json
# (--overwrite: the frames are complete, and a resumed run would skip them.)
"$binary" render "$source/scenes/ball.json" "${small[@]}" --out "$out/localized" --overwrite 2>&1 | tee "$out/second.log"
grep -q "records loaded from" "$out/second.log" || { echo "the second run did not load the static cache"; exit 1; }
# A damaged cache file is rejected, recomputed and replaced: never a crash or a wrong picture.
head -c 100 "$out/localized/ball.irrcache" > "$out/cut" && mv "$out/cut" "$out/localized/ball.irrcache"
"$binary" render "$source/scenes/ball.json" "${small[@]}" --out "$out/localized" --overwrite 2>&1 | tee "$out/third.log"
grep -q "computed in .*truncated" "$out/third.log" || { echo "the truncated cache was not recomputed"; exit 1; }
# bake writes the cache a later render then loads.
"$binary" bake "$source/scenes/ball.json" --size 16x12 --photons 5000 --gather-samples 32 --out "$out/baked"
"$binary" render "$source/scenes/ball.json" "${small[@]}" --out "$out/baked" > "$out/baked.log" 2>&1
grep -q "records loaded from" "$out/baked.log" || { echo "render did not load the baked cache"; exit 1; }
echo "ok"
