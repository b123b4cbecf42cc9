#!/usr/bin/env bash
# Sets up, builds what the demo needs (the steadylight program only, not the tests and
# benchmarks), renders the demo animation BALL into out/ball/, writes its HTML report (and an
# MP4 where ffmpeg is installed) and says where to look. Extra arguments go to `render`, e.g.
#   bash scripts/demo.sh --spp 64
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh --target steadylight
out=out/ball
video=()
command -v ffmpeg >/dev/null && video=(--video "$out/ball.mp4")
./build/steadylight render scenes/ball.json --out "$out" "${video[@]}" "$@"
./build/steadylight report "$out"
echo
echo "demo: the frames are in $out/ (ball_<frame>.png, and ball_<frame>.exr with every layer)"
echo "demo: open the report: $PWD/$out/report.html"
[ ${#video[@]} -eq 0 ] || echo "demo: the video: $PWD/$out/ball.mp4"
