#!/usr/bin/env bash
# Names and links that would send a render's files outside its output folder: a scene name with a
# path in it is refused before any work; a symbolic link put where a frame file or the folder's
# lock file goes is an error, and the file it points at stays as it was; a stale temporary that is
# a link is removed, never written through; the user's own --out may be a link.
set -euo pipefail
binary=$1 source=$2 out=$3
tiny=(--frames 0 --size 16x12 --spp 1 --photons 2000 --caustic-photons 0 --gather-samples 32 --no-progress)
fail() { echo "FAIL: $*"; exit 1; }
expect_failure() {  # expect_failure LOG REGEX ARGS...: the render fails saying REGEX
  local log=$1 regex=$2
  shift 2
  "$binary" render "$@" > "$log" 2>&1 && fail "accepted: $*"
  grep -Eq -- "$regex" "$log" || { cat "$log"; fail "the message does not match /$regex/"; }
}

rm -rf "$out"
mkdir -p "$out"

# A scene named "../escaped": refused, naming /name, and nothing written above the folder.
sed 's/"name": "ball"/"name": "..\/escaped"/' "$source/scenes/ball.json" > "$out/escape.json"
expect_failure "$out/escape.log" 'escape.json:/name: the scene name "../escaped" holds a path separator' \
  "$out/escape.json" "${tiny[@]}" --out "$out/outer/inner"
[ -z "$(find "$out" -name 'escaped*')" ] || fail "files named escaped* were written: $(find "$out" -name 'escaped*')"

# A link where a frame file goes: an error naming it; what it points at is untouched.
echo precious > "$out/victim"
mkdir -p "$out/linked_frame"
ln -s "$out/victim" "$out/linked_frame/ball_0000.png"
expect_failure "$out/linked_frame.log" 'ball_0000.png: it is a symbolic link' "$source/scenes/ball.json" "${tiny[@]}" \
  --out "$out/linked_frame"
[ "$(cat "$out/victim")" = precious ] || fail "the link's target was written"

# A link where the folder's lock file goes (dangling: opening it would create its target).
mkdir -p "$out/linked_lock"
ln -s "$out/created_elsewhere" "$out/linked_lock/.steadylight.lock"
expect_failure "$out/linked_lock.log" 'steadylight.lock: cannot open it as a lock file: .*symbolic link' \
  "$source/scenes/ball.json" "${tiny[@]}" --out "$out/linked_lock"
[ ! -e "$out/created_elsewhere" ] || fail "the lock file's link created its target"

# A stale temporary that is a link: removed and replaced, never written through.
mkdir -p "$out/linked_partial"
ln -s "$out/victim" "$out/linked_partial/ball_0000.exr.partial"
"$binary" render "$source/scenes/ball.json" "${tiny[@]}" --out "$out/linked_partial" > "$out/linked_partial.log" 2>&1 \
  || { cat "$out/linked_partial.log"; fail "render with a linked temporary"; }
[ "$(cat "$out/victim")" = precious ] || fail "written through the temporary's link"
[ -f "$out/linked_partial/ball_0000.exr" ] && [ ! -L "$out/linked_partial/ball_0000.exr" ] || fail "no frame written"

# The user's own --out may be a link: the files land in the folder it points at.
mkdir -p "$out/real"
ln -s "$out/real" "$out/link_to_real"
"$binary" render "$source/scenes/ball.json" "${tiny[@]}" --out "$out/link_to_real" > "$out/link_out.log" 2>&1 \
  || { cat "$out/link_out.log"; fail "render into a linked --out"; }
[ -f "$out/real/ball_0000.exr" ] || fail "no frame in the folder --out links to"
cmp "$out/real/ball_0000.exr" "$out/linked_partial/ball_0000.exr" || fail "the frames differ"
echo ok
