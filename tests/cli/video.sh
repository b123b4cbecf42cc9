#!/usr/bin/env bash
# `--video`: renders three tiny BALL frames into a folder whose name has a space, encodes them
# with ffmpeg and checks with ffprobe that the MP4 is H.264, yuv420p, 3 frames at the scene's
# frame rate, with odd image sizes padded to even; that a resumed run encodes the PNGs of the
# frames it skipped too; that RGBA frames (--transparent-background) are encoded too; and that a
# video ffmpeg cannot write is an error that keeps the frames.
# Without ffmpeg it is skipped (exit 77), or fails under CI=true.
set -euo pipefail
binary=$1 source=$2 out=$3
source "$source/tests/support/skip.sh"

command -v ffmpeg >/dev/null && command -v ffprobe >/dev/null || skip_without_tool "ffmpeg/ffprobe not installed"
rm -rf "$out"
mkdir -p "$out"
"$binary" render "$source/scenes/ball.json" --method path --frames 5-7 --spp 1 --size 41x31 \
  --out "$out/frames dir" --video "$out/my video.mp4" --no-progress
[ -s "$out/my video.mp4" ] || { echo "no video written"; exit 1; }
[ ! -e "$out/my video.mp4.partial" ] || { echo "temporary video left behind"; exit 1; }
probe() { ffprobe -v error -select_streams v:0 -count_frames -show_entries "stream=$1" -of default=nw=1:nk=1 "$out/my video.mp4"; }
fps=$(python3 -c "import json; print(json.load(open('$source/scenes/ball.json')).get('frames', {}).get('fps', 24))")
echo "codec=$(probe codec_name) pix_fmt=$(probe pix_fmt) frames=$(probe nb_read_frames) rate=$(probe r_frame_rate) size=$(probe width)x$(probe height) scene fps=$fps"
[ "$(probe codec_name)" = h264 ] || { echo "not H.264"; exit 1; }
[ "$(probe pix_fmt)" = yuv420p ] || { echo "not yuv420p"; exit 1; }
[ "$(probe nb_read_frames)" = 3 ] || { echo "not 3 frames"; exit 1; }
python3 -c "import sys; n, d = '$(probe r_frame_rate)'.split('/'); sys.exit(abs(int(n) / int(d) - float('$fps')) > 1e-3)" \
  || { echo "frame rate differs from the scene's"; exit 1; }
[ "$(probe width)x$(probe height)" = 42x32 ] || { echo "odd size not padded to even"; exit 1; }
# Resumed: frames 5-6 are complete from an earlier run and skipped, yet the video has all three.
"$binary" render "$source/scenes/ball.json" --method path --frames 5-6 --spp 1 --size 16x12 --out "$out/resumed" --no-progress
"$binary" render "$source/scenes/ball.json" --method path --frames 5-7 --spp 1 --size 16x12 --out "$out/resumed" \
  --video "$out/resumed.mp4" --no-progress 2>&1 | tee "$out/resumed.log"
grep -q "1 frame(s) written, 2 complete ones skipped" "$out/resumed.log" || { echo "frames 5-6 were not skipped"; exit 1; }
[ "$(ffprobe -v error -select_streams v:0 -count_frames -show_entries stream=nb_read_frames -of default=nw=1:nk=1 "$out/resumed.mp4")" = 3 ] \
  || { echo "the resumed video does not have 3 frames"; exit 1; }
# RGBA frames: laid over black (ffmpeg's premultiply filter) before the padding and yuv420p.
"$binary" render "$source/scenes/ball.json" --method path --frames 5-6 --spp 1 --size 41x31 --out "$out/alpha" \
  --transparent-background --video "$out/alpha.mp4" --no-progress
[ "$(ffprobe -v error -select_streams v:0 -count_frames -show_entries stream=nb_read_frames -of default=nw=1:nk=1 "$out/alpha.mp4")" = 2 ] \
  || { echo "the video of RGBA frames does not have 2 frames"; exit 1; }
# A video ffmpeg cannot write is an error (exit status 1) after the frames are written.
if "$binary" render "$source/scenes/ball.json" --method path --frames 5 --spp 1 --size 16x12 --out "$out/failing" \
     --video /dev/null/x.mp4 --no-progress > "$out/failing.log" 2>&1; then
  echo "an unwritable video did not fail"; exit 1
fi
grep -q "error: --video: cannot write /dev/null/x.mp4: ffmpeg exited with status" "$out/failing.log" \
  || { cat "$out/failing.log"; echo "no clear message for the failed video"; exit 1; }
[ -s "$out/failing/ball_0005.png" ] || { echo "the frame was not kept"; exit 1; }
echo "ok"
