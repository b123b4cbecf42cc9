#!/usr/bin/env bash
# Resume after an interruption gives the same files as an uninterrupted run. Renders three tiny
# BALL frames into A; into B renders with the test-only hook STEADYLIGHT_TEST_INTERRUPT_AFTER_FRAMES=1
# (the renderer raises SIGINT itself inside frame 1), expects exit 130 with frame 0 whole and
# nothing of frames 1-2, not even temporary files, then runs again and compares the images with
# A byte for byte (stats.json holds timings, so only images and the static cache are compared).
# Then: a truncated frame is rendered again, --overwrite renders everything again, other settings
# (also another --exposure) are refused, and a real SIGINT from outside stops a render cleanly.
set -euo pipefail
binary=$1 source=$2 out=$3
scene=$source/scenes/ball.json
tiny=(--size 40x30 --spp 1 --photons 2000 --caustic-photons 0 --gather-samples 32 --no-progress)
small=(--frames 0-2 "${tiny[@]}")
fail() { echo "FAIL: $*"; exit 1; }

same_images() {  # same_images DIR_A DIR_B: every image and the static cache byte-identical
  for file in "$1"/*.exr "$1"/*.png "$1"/ball.irrcache; do
    cmp "$file" "$2/$(basename "$file")" || fail "$(basename "$file") differs"
  done
}
no_temporaries() { ! ls "$1" | grep -q '\.partial$' || fail "temporary files left in $1: $(ls "$1")"; }

rm -rf "$out"
"$binary" render "$scene" "${small[@]}" --out "$out/A" > "$out.A.log" 2>&1 || { cat "$out.A.log"; fail "render A"; }

# Interrupted inside frame 1.
status=0
STEADYLIGHT_TEST_INTERRUPT_AFTER_FRAMES=1 "$binary" render "$scene" "${small[@]}" --out "$out/B" > "$out/B.log" 2>&1 || status=$?
cat "$out/B.log"
[ $status -eq 130 ] || fail "interrupted render exited with $status, not 130"
grep -q "1 frame(s) finished in this run: 0, 2 left (1-2)" "$out/B.log" || fail "no resume message"
for ext in exr png stats.json manifest.json; do [ -s "$out/B/ball_0000.$ext" ] || fail "frame 0 lacks .$ext"; done
! ls "$out/B" | grep -q 'ball_000[12]' || fail "files of the dropped frame 1 or of frame 2: $(ls "$out/B")"
no_temporaries "$out/B"

# The next run resumes: frame 0 skipped, frames 1-2 rendered, images as in A.
"$binary" render "$scene" "${small[@]}" --out "$out/B" 2>&1 | tee "$out/resume.log"
grep -q "complete from an earlier run, skipped: 0 " "$out/resume.log" || fail "frame 0 was not skipped"
grep -q "2 frame(s) written, 1 complete ones skipped" "$out/resume.log" || fail "summary counts"
same_images "$out/A" "$out/B"

# A truncated file makes its frame incomplete: only that frame is rendered again.
truncate -s 100 "$out/B/ball_0001.exr"
"$binary" render "$scene" "${small[@]}" --out "$out/B" 2>&1 | tee "$out/truncated.log"
grep -q "frame 1: rendering it again: ball_0001.exr has 100 bytes" "$out/truncated.log" || fail "truncation unnoticed"
grep -q "1 frame(s) written, 2 complete ones skipped" "$out/truncated.log" || fail "truncated: counts"
same_images "$out/A" "$out/B"

# --overwrite renders every frame again.
"$binary" render "$scene" "${small[@]}" --out "$out/B" --overwrite 2>&1 | tee "$out/overwrite.log"
grep -q "3 frame(s) written, 0 complete ones skipped" "$out/overwrite.log" || fail "--overwrite did not render all"
same_images "$out/A" "$out/B"

# Other settings into the same folder are refused, and leave it as it was.
"$binary" render "$scene" "${small[@]}" --out "$out/B" --cache-accuracy 0.5 > "$out/other.log" 2>&1 && fail "other settings accepted"
grep -q "ball.settings.json: the frames in this folder were rendered with other settings (/photon/cache/accuracy: 0.25 -> 0.5)" \
  "$out/other.log" || { cat "$out/other.log"; fail "other settings: message"; }
# The output settings shape the images too: another exposure is other settings.
"$binary" render "$scene" "${small[@]}" --out "$out/B" --exposure 1 > "$out/exposure.log" 2>&1 && fail "other exposure accepted"
grep -q "other settings (/output/exposure_ev: 0.0 -> 1.0)" "$out/exposure.log" || { cat "$out/exposure.log"; fail "exposure: message"; }

# A real SIGINT from outside, once the first frame of a longer render is written.
"$binary" render "$scene" "${tiny[@]}" --out "$out/C" > "$out/C.log" 2>&1 &
pid=$!
for _ in $(seq 300); do
  [ -e "$out/C/ball_0000.manifest.json" ] && break
  kill -0 $pid 2>/dev/null || { cat "$out/C.log"; fail "the render ended early"; }
  sleep 0.05
done
kill -INT $pid
status=0; wait $pid || status=$?
cat "$out/C.log"
[ $status -eq 130 ] || fail "SIGINT: exit status $status, not 130"
no_temporaries "$out/C"
for manifest in "$out"/C/*.manifest.json; do
  frame=${manifest%.manifest.json}
  for ext in exr png stats.json; do [ -s "$frame.$ext" ] || fail "$frame.$ext missing"; done
done
[ "$(ls "$out"/C/*.exr | wc -l)" -eq "$(ls "$out"/C/*.manifest.json | wc -l)" ] || fail "an image without a manifest"
echo "ok"
