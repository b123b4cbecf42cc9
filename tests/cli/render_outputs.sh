#!/usr/bin/env bash
# Renders two small BALL frames and checks that exactly the expected files appear, whole.
set -euo pipefail
binary=$1 source=$2 out=$3
rm -rf "$out"
"$binary" render "$source/scenes/ball.json" --frames 3-4 --spp 1 --size 16x12 --out "$out" --no-progress
for f in 3 4; do
  for ext in exr png; do
    file="$out/ball_000$f.$ext"
    [ -s "$file" ] || { echo "missing $file"; exit 1; }
  done
done
[ "$(ls "$out" | wc -l)" -eq 4 ] || { echo "unexpected files:"; ls "$out"; exit 1; }
echo "ok"
