#!/usr/bin/env bash
# A render killed with SIGKILL at random moments, and resumed each time, ends with the files of
# an uninterrupted render, and never leaves a truncated final file. Renders 20 small BALL frames
# into A; then into B starts the same render 20 times, each killed with SIGKILL after a random
# delay within half the time the frames it has left took in A (so that it may die in the static
# pass, inside a frame or while a frame is written, and the runs together get through the render).
# After every kill each final file in B (image, statistics, manifest, static cache) is whole:
# the images and the cache equal A's byte for byte (only .partial temporaries may be left).
# A last run completes B: every image and the cache as in A, and no temporary left.
set -euo pipefail
binary=$1 source=$2 out=$3
scene=$source/scenes/ball.json
args=(--frames 0-19 --size 80x60 --spp 4 --photons 20000 --caustic-photons 0 --gather-samples 128 --no-progress)
fail() { echo "FAIL: $*"; exit 1; }

rm -rf "$out"
mkdir -p "$out"
start=$(date +%s%N)
"$binary" render "$scene" "${args[@]}" --out "$out/A" > "$out/A.log" 2>&1 || { cat "$out/A.log"; fail "render A"; }
duration_ms=$(( ($(date +%s%N) - start) / 1000000 ))
echo "uninterrupted: ${duration_ms} ms"

# Every final file in B is whole: images and the cache equal A's; JSON files parse.
check_whole() {
  local json=()
  for file in "$out"/B/*; do
    case $file in
      *.exr|*.png|*.irrcache) cmp -s "$file" "$out/A/$(basename "$file")" || fail "after kill $1: $(basename "$file") differs from A's" ;;
      *.json) json+=("$file") ;;
    esac
  done
  [ ${#json[@]} -eq 0 ] || python3 -c 'import json, sys
for name in sys.argv[1:]: json.load(open(name))' "${json[@]}" || fail "after kill $1: a JSON file is not whole"
}

complete_frames() {
  local n=0 manifest
  for manifest in "$out"/B/*.manifest.json; do [ -e "$manifest" ] && n=$((n + 1)); done
  echo $n
}

RANDOM=7  # the same delays in every run of the test
kills=0
for i in $(seq 20); do
  "$binary" render "$scene" "${args[@]}" --out "$out/B" >> "$out/B.log" 2>&1 &
  pid=$!
  left=$(( 20 - $(complete_frames) ))
  delay_ms=$(( RANDOM % (duration_ms * left / 40 + 1) ))
  sleep "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
  if kill -KILL $pid 2>/dev/null && [ $left -gt 0 ]; then kills=$((kills + 1)); fi
  wait $pid 2>/dev/null || true
  check_whole "$i (after ${delay_ms} ms)"
done
echo "killed $kills of 20 runs with frames left to render; frames complete before the last run: $(complete_frames)"
[ $kills -ge 8 ] || fail "only $kills runs were killed with frames left to render"

"$binary" render "$scene" "${args[@]}" --out "$out/B" > "$out/last.log" 2>&1 || { cat "$out/last.log"; fail "last run"; }
for file in "$out"/A/*.exr "$out"/A/*.png "$out"/A/ball.irrcache; do
  cmp "$file" "$out/B/$(basename "$file")" || fail "$(basename "$file") differs after resuming"
done
! ls "$out/B" | grep -q '\.partial$' || fail "temporary files left: $(ls "$out/B" | grep '\.partial$')"
"$binary" render "$scene" "${args[@]}" --out "$out/B" --check-complete > /dev/null || fail "--check-complete: frames missing"
echo "ok"
