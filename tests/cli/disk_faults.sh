#!/usr/bin/env bash
# Output folders that fail: a full disk and a read-only file system (small tmpfs mounts, so
# root only: skipped, saying why, where mounting is not possible, and failed under CI=true), a cache file that is a folder
# and an output path through a file. A full disk stops the render with a clear error naming the
# file (not an internal error), leaves no truncated final file (every image present equals an
# uninterrupted render's), and the same command resumes once there is space. The others are
# refused before any work.
set -euo pipefail
binary=$1 source=$2 out=$3
scene=$source/scenes/ball.json
source "$source/tests/support/skip.sh"
args=(--frames 0-9 --size 160x120 --spp 2 --photons 5000 --caustic-photons 0 --gather-samples 32 --no-progress)
fail() { echo "FAIL: $*"; exit 1; }
expect_error() {  # expect_error LOG REGEX: exit status 1 was seen; the log holds REGEX and no internal error
  grep -q "$2" "$1" || { cat "$1"; fail "no message matching: $2"; }
  ! grep -q "internal error" "$1" || { cat "$1"; fail "an internal error"; }
}

cleanup() { mountpoint -q "$out/disk" && umount "$out/disk"; true; }
trap cleanup EXIT
cleanup
rm -rf "$out"
mkdir -p "$out/disk"

# Refused before any work: a cache file that is a folder, an output folder through a file.
mkdir -p "$out/folder_cache/ball.irrcache"
"$binary" render "$scene" "${args[@]}" --out "$out/folder_cache" > "$out/folder_cache.log" 2>&1 && fail "a cache folder accepted"
expect_error "$out/folder_cache.log" "error: --cache-file: .*ball.irrcache is a folder, not a file"
touch "$out/a_file"
"$binary" render "$scene" "${args[@]}" --out "$out/a_file/frames" > "$out/through_file.log" 2>&1 && fail "--out through a file accepted"
expect_error "$out/through_file.log" "error: --out: .*a_file/frames: cannot create the folder: Not a directory"

"$binary" render "$scene" "${args[@]}" --out "$out/A" > "$out/A.log" 2>&1 || { cat "$out/A.log"; fail "render A"; }
needed_kb=$(du -sk "$out/A" | cut -f1)

if ! mount -t tmpfs -o size=$((needed_kb / 2))k tmpfs "$out/disk" 2> "$out/mount.log"; then
  skip_without_tool "full disk and read-only folder: cannot mount a tmpfs here: $(cat "$out/mount.log")"
fi

# A disk with room for half the outputs.
status=0
"$binary" render "$scene" "${args[@]}" --out "$out/disk/B" > "$out/full.log" 2>&1 || status=$?
cat "$out/full.log"
[ $status -eq 1 ] || fail "a full disk: exit status $status, not 1"
expect_error "$out/full.log" "error: cannot write $out/disk/B/.*: .*No space left on device"
for file in "$out"/disk/B/*.exr "$out"/disk/B/*.png "$out"/disk/B/ball.irrcache; do
  [ -e "$file" ] || continue
  cmp -s "$file" "$out/A/$(basename "$file")" || fail "$(basename "$file") is not whole"
done
written=$(ls "$out"/disk/B/*.manifest.json 2>/dev/null | wc -l || true)
echo "frames complete when the disk was full: $written"
[ "$written" -lt 10 ] || fail "the disk did not fill"

# Room again: the same command completes the render.
mount -o remount,size=$((needed_kb * 2))k "$out/disk"
"$binary" render "$scene" "${args[@]}" --out "$out/disk/B" > "$out/resumed.log" 2>&1 || { cat "$out/resumed.log"; fail "resume"; }
for file in "$out"/A/*.exr "$out"/A/*.png "$out"/A/ball.irrcache; do
  cmp "$file" "$out/disk/B/$(basename "$file")" || fail "$(basename "$file") differs after resuming"
done
! ls "$out/disk/B" | grep -q '\.partial$' || fail "temporary files left"

# A read-only file system: refused before any work.
mount -o remount,ro "$out/disk"
"$binary" render "$scene" "${args[@]}" --out "$out/disk/C" > "$out/read_only.log" 2>&1 && fail "a read-only disk accepted"
expect_error "$out/read_only.log" "error: --out: .*disk/C: cannot create the folder: Read-only file system"
"$binary" render "$scene" "${args[@]}" --out "$out/disk/B" --overwrite > "$out/read_only_b.log" 2>&1 && fail "a read-only folder accepted"
expect_error "$out/read_only_b.log" "error: --out: .*disk/B: cannot write into the folder: Read-only file system"
! grep -q "static photon paths" "$out/read_only_b.log" || fail "work began on a read-only folder"
echo "ok"
