#!/usr/bin/env bash
# Many processes on one output folder, without a scheduler (docs/farm.md):
# 1. Same pictures: BALL frames 0-5 rendered by one process (2 threads, static cache computed)
#    and by `bake --segment 0` plus two `render --require-cache` of the chunks 0-2 and 3-5 with
#    1 thread each (cache loaded from its file): images byte-identical.
# 2. --require-cache without a cache file is an error naming it; --segment past the last is refused.
# 3. Two plain renders started at once on one folder share its frames: every frame written
#    once, the static cache computed once, images as in 1, no claim or .partial file left.
# 4. A claim of this host whose process is gone is taken over at once and the frame's stale
#    .partial removed; a fresh claim of another host is left to it for now, waited for at the
#    end, and taken over once it is no longer refreshed (lock times shortened for the test);
#    --check-complete fails naming a frame that is not complete.
set -euo pipefail
binary=$1 source=$2 out=$3
scene=$source/scenes/ball.json
photon=(--size 40x30 --photons 4000 --caustic-photons 0 --gather-samples 32)  # what bake takes too
small=("${photon[@]}" --spp 2 --no-progress)
fail() { echo "FAIL: $*"; exit 1; }
same_images() {  # same_images DIR_A DIR_B FRAMES...: those frames' EXR and PNG byte-identical
  local a=$1 b=$2; shift 2
  for frame in "$@"; do
    for ext in exr png; do
      file=$(printf "ball_%04d.%s" "$frame" "$ext")
      cmp "$a/$file" "$b/$file" || fail "$file differs between $a and $b"
    done
  done
}
no_leftovers() { ! ls -A "$1" | grep -Eq '\.(partial|claim|lock|break|tmp)$' || fail "left in $1: $(ls -A "$1")"; }

rm -rf "$out"
mkdir -p "$out"
# 1. One process against bake + chunks.
"$binary" render "$scene" "${small[@]}" --frames 0-5 --threads 2 --out "$out/one" > "$out/one.log" 2>&1 \
  || { cat "$out/one.log"; fail "one-process render"; }
grep -q "static cache: .* records computed" "$out/one.log" || fail "the one-process render did not compute the cache"
"$binary" bake "$scene" "${photon[@]}" --segment 0 --threads 1 --out "$out/chunks" > "$out/bake.log" 2>&1 \
  || { cat "$out/bake.log"; fail "bake --segment 0"; }
for chunk in 0-2 3-5; do
  "$binary" render "$scene" "${small[@]}" --frames $chunk --threads 1 --require-cache --out "$out/chunks" \
    > "$out/chunk_$chunk.log" 2>&1 || { cat "$out/chunk_$chunk.log"; fail "chunk $chunk"; }
  grep -q "static cache: .* records loaded from" "$out/chunk_$chunk.log" || fail "chunk $chunk did not load the cache"
done
same_images "$out/one" "$out/chunks" 0 1 2 3 4 5
cmp "$out/one/ball.irrcache" "$out/chunks/ball.irrcache" || fail "the baked cache differs from the rendered one"

# 2. Errors.
status=0
"$binary" render "$scene" "${small[@]}" --frames 0 --require-cache --out "$out/nocache" > "$out/nocache.log" 2>&1 || status=$?
cat "$out/nocache.log"
[ $status -eq 1 ] || fail "--require-cache without a cache: exit status $status, not 1"
grep -q "nocache/ball.irrcache: the static cache of frames 0-59 is not usable (missing), and --require-cache does not compute it" \
  "$out/nocache.log" || fail "--require-cache: message"
! ls "$out/nocache" | grep -q 'ball_0000' || fail "--require-cache without a cache wrote frame files"
status=0
"$binary" bake "$scene" "${photon[@]}" --segment 1 --out "$out/nocache" > "$out/segment.log" 2>&1 || status=$?
[ $status -eq 1 ] && grep -q "error: --segment: 1 is not a segment of .*ball.json: it has 1 (0 to 0" "$out/segment.log" \
  || { cat "$out/segment.log"; fail "bake --segment 1: status $status"; }

# 3. Two renders at once on one folder.
"$binary" render "$scene" "${small[@]}" --frames 0-5 --threads 1 --out "$out/shared" > "$out/shared_a.log" 2>&1 &
a=$!
"$binary" render "$scene" "${small[@]}" --frames 0-5 --threads 1 --out "$out/shared" > "$out/shared_b.log" 2>&1 &
b=$!
wait $a || { cat "$out/shared_a.log"; fail "shared render A"; }
wait $b || { cat "$out/shared_b.log"; fail "shared render B"; }
cat "$out/shared_a.log" "$out/shared_b.log"
written=0
for count in $(cat "$out/shared_a.log" "$out/shared_b.log" | sed -n 's/.* \([0-9]*\) frame(s) written.*/\1/p'); do
  written=$((written + count))
done
[ "$written" -eq 6 ] || fail "the two renders wrote $written frames, not 6 (each once)"
computed=$(cat "$out/shared_a.log" "$out/shared_b.log" | grep -c "records computed" || true)
[ "$computed" -eq 1 ] || fail "the static cache was computed $computed times, not once"
same_images "$out/one" "$out/shared" 0 1 2 3 4 5
no_leftovers "$out/shared"

# 4. Dead and live claims.
mkdir -p "$out/claims"
sleep 0 & gone=$!; wait $gone
printf '{"host": "%s", "pid": %d, "time": "then"}\n' "$(hostname)" "$gone" > "$out/claims/ball_0002.claim"
echo "half a frame" > "$out/claims/ball_0002.exr.partial"
printf '{"host": "elsewhere", "pid": 1, "time": "now"}\n' > "$out/claims/ball_0003.claim"
STEADYLIGHT_TEST_LOCK_TIMES=0.2,3 "$binary" render "$scene" "${small[@]}" --frames 0-3 --out "$out/claims" \
  > "$out/claims.log" 2>&1 || { cat "$out/claims.log"; fail "render with claims"; }
cat "$out/claims.log"
grep -q "frame 2: took over a dead claim (host $(hostname), pid $gone, .*: its process $gone on this host is gone)" \
  "$out/claims.log" || fail "the dead claim was not taken over"
grep -q "frame 2: removed the stale ball_0002.exr.partial" "$out/claims.log" || fail "stale .partial not removed"
grep -q "frame 3: claimed by another process (host elsewhere, pid 1, refreshed [0-9]* s ago), left to it for now" \
  "$out/claims.log" || fail "the live claim was not respected"
grep -q "waiting for frame(s) 3, claimed by other processes" "$out/claims.log" || fail "no wait for the claimed frame"
grep -q "frame 3: took over a dead claim (host elsewhere, pid 1, .*: not refreshed for [0-9]* s, the limit is 3 s)" \
  "$out/claims.log" || fail "the claim that went stale was not taken over"
grep -q "4 frame(s) written, 0 complete ones skipped" "$out/claims.log" || fail "summary after taking a claim over"
no_leftovers "$out/claims"
same_images "$out/one" "$out/claims" 0 1 2 3
status=0
"$binary" render "$scene" "${small[@]}" --frames 0-4 --check-complete --out "$out/claims" > "$out/check.log" 2>&1 || status=$?
cat "$out/check.log"
[ $status -eq 1 ] && grep -q "claims: 1 of the 5 selected frame(s) are not complete: 4" "$out/check.log" \
  || fail "--check-complete: status $status"
! ls "$out/claims" | grep -q 'ball_0004\.exr' || fail "--check-complete rendered a frame"
echo "ok"
