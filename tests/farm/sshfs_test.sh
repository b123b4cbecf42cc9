#!/usr/bin/env bash
# One output folder shared over a network file system, as two machines see it: sshd on
# 127.0.0.1, the folder mounted twice with sshfs, one render per mount with its own host name
# (unshare --uts), the lock times shortened for the test (STEADYLIGHT_TEST_LOCK_TIMES) and the
# mounts' attribute cache kept below the stale time, as docs/farm.md asks.
# 0. Shows why flock is not used: an exclusive flock through each mount, both granted at once.
# 1. Two renders at once, BALL 80x60 frames 0-11: every frame written once, the static cache
#    computed once, frames byte-identical to a render on the local disk, the settings file
#    listing every frame, no claim, lock or temporary file left.
# 2. One of two renders killed (SIGKILL) while it holds a frame: the other takes that frame over
#    once its claim is no longer refreshed, removes what it left, and every frame ends
#    identical to the local render.
# Skipped (77) without sshfs, sshd or root, except under CI=true, where it fails; skipped also
# there where the kernel lacks FUSE or UTS namespaces.
#   sshfs_test.sh BINARY SOURCE_DIR OUT_DIR
set -euo pipefail
binary=$1 source=$2 out=$3
scene=$source/scenes/ball.json
options=(--size 80x60 --frames 0-11 --spp 4 --photons 20000 --caustic-photons 2000 --gather-samples 64 --threads 1
  --no-progress)
export STEADYLIGHT_TEST_LOCK_TIMES=0.5,5  # refresh, stale: stale > refresh + the mounts' 2 s caches
fail() { echo "FAIL: $*"; exit 1; }
source "$source/tests/support/skip.sh"

for tool in sshfs /usr/sbin/sshd ssh-keygen unshare fusermount3; do
  command -v "$tool" > /dev/null || skip_without_tool "$tool is not installed (scripts/setup.sh installs sshfs and openssh-server)"
done
[ "$(id -u)" -eq 0 ] || skip_without_tool "two host names (unshare --uts) and sshd need root"
# Kernel features, which no package brings: skipped, saying so, also under CI.
[ -c /dev/fuse ] || { echo "skip: no /dev/fuse: this kernel or container has no FUSE"; exit 77; }
unshare --uts true 2> /dev/null || { echo "skip: unshare --uts is not allowed here (no UTS namespaces)"; exit 77; }

rm -rf "$out"
mkdir -p "$out"
work=$(mktemp -d /tmp/steadylight-sshfs.XXXXXX)
cleanup() {
  for mount in "$work/alpha" "$work/beta"; do fusermount3 -u -z "$mount" 2> /dev/null || true; done
  [ -f "$work/sshd.pid" ] && kill "$(cat "$work/sshd.pid")" 2> /dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
mkdir -p "$work/shared" "$work/alpha" "$work/beta" /run/sshd
ssh-keygen -q -t ed25519 -N '' -f "$work/host_key"
ssh-keygen -q -t ed25519 -N '' -f "$work/client_key"
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
cat > "$work/sshd_config" << EOF
Port $port
ListenAddress 127.0.0.1
HostKey $work/host_key
PidFile $work/sshd.pid
AuthorizedKeysFile $work/client_key.pub
PermitRootLogin prohibit-password
PasswordAuthentication no
StrictModes no
Subsystem sftp internal-sftp
EOF
/usr/sbin/sshd -f "$work/sshd_config" -E "$work/sshd.log" || { cat "$work/sshd.log"; fail "sshd did not start"; }
ssh_options=(-p "$port" -o "IdentityFile=$work/client_key" -o StrictHostKeyChecking=no -o UserKnownHostsFile=/dev/null
  -o BatchMode=yes -o LogLevel=ERROR)
for _ in $(seq 50); do ssh "${ssh_options[@]}" root@127.0.0.1 true 2> /dev/null && break; sleep 0.1; done
# sshfs's own attribute and directory caches (20 s by default) and the kernel's (1 s), kept
# below the stale time; the defaults are fine with the default stale time of 120 s.
for mount in alpha beta; do
  sshfs "${ssh_options[@]}" -o dcache_timeout=1 "root@127.0.0.1:$work/shared" "$work/$mount" \
    || fail "sshfs could not mount the folder on $work/$mount"
done

# 0. flock through the two mounts.
flock -x "$work/alpha/flock.test" sleep 2 &
sleep 0.5
if flock -x -n "$work/beta/flock.test" true; then
  echo "as expected: an exclusive flock through each mount is granted at once; steadylight does not use flock"
else
  echo "flock held across the two mounts here"
fi
wait
rm -f "$work/shared/flock.test"

# The reference: one render on the local disk.
"$binary" render "$scene" "${options[@]}" --out "$out/local" > "$out/local.log" 2>&1 \
  || { cat "$out/local.log"; fail "the local render"; }

# render_as HOST DIR LOG: a render with its own host name, in the background ($! is its pid).
render_as() {
  unshare --uts sh -c 'hostname "$0"; exec "$@"' "$1" "$binary" render "$scene" "${options[@]}" --out "$2" \
    > "$3" 2>&1 &
}
same_frames() {  # same_frames DIR: every frame's EXR and PNG as in the local render
  local number ext file
  for number in $(seq 0 11); do
    for ext in exr png; do
      file=$(printf "ball_%04d.%s" "$number" "$ext")
      cmp "$out/local/$file" "$1/$file" || fail "$1/$file differs from the local render"
    done
  done
}
frames_written() { cat "$@" | sed -n 's/.* \([0-9]*\) frame(s) written.*/\1/p' | awk '{ n += $1 } END { print n + 0 }'; }
leftovers() { ls -A "$1" | grep -E '\.(partial|claim|lock|break|tmp)$|^\.fuse_hidden|^\.steadylight' || true; }

# 1. Two renders at once.
render_as alpha "$work/alpha/one" "$out/one_alpha.log"
a=$!
render_as beta "$work/beta/one" "$out/one_beta.log"
b=$!
wait $a || { cat "$out/one_alpha.log"; fail "render alpha"; }
wait $b || { cat "$out/one_beta.log"; fail "render beta"; }
cat "$out/one_alpha.log" "$out/one_beta.log"
[ "$(frames_written "$out/one_alpha.log" "$out/one_beta.log")" -eq 12 ] || fail "the two renders did not write 12 frames, each once"
computed=$(cat "$out/one_alpha.log" "$out/one_beta.log" | grep -c "records computed" || true)
[ "$computed" -eq 1 ] || fail "the static cache was computed $computed times, not once"
same_frames "$work/shared/one"
python3 -c 'import json, sys; frames = json.load(open(sys.argv[1]))["frames"]; sys.exit(frames != "0-11")' \
  "$work/shared/one/ball.settings.json" || fail "the settings file does not list frames 0-11"
[ -z "$(leftovers "$work/shared/one")" ] || fail "left in the folder: $(leftovers "$work/shared/one")"
echo "1: every frame written once, the cache computed once, frames identical"

# 2. One render killed while it holds a frame, after it wrote some. A claim seen a moment before
# the kill may be released by then (its frame written, or found written by beta), so the frame
# held is the unfinished one whose claim the dead render left behind; the scene is tried again
# in a new folder when there is none.
for attempt in 1 2 3 4 5; do
  dir=kill$attempt
  render_as alpha "$work/alpha/$dir" "$out/${dir}_alpha.log"
  a=$!
  render_as beta "$work/beta/$dir" "$out/${dir}_beta.log"
  b=$!
  held=""
  for _ in $(seq 3000); do
    held=$(grep -l '"host":"alpha"' "$work/shared/$dir/"ball_00{0[4-9],1[01]}.claim 2> /dev/null | head -n 1 || true)
    [ -n "$held" ] && break
    sleep 0.01
  done
  [ -n "$held" ] || fail "render alpha never held a frame"
  kill -KILL $a
  wait $a 2> /dev/null || true
  held=""
  for claim in $(grep -l '"host":"alpha"' "$work/shared/$dir/"ball_*.claim 2> /dev/null || true); do
    [ -f "${claim%.claim}.manifest.json" ] || held=$claim
  done
  [ -n "$held" ] && break
  wait $b || { cat "$out/${dir}_beta.log"; fail "render beta"; }
  echo "alpha held no frame when it was killed (attempt $attempt)"
done
[ -n "$held" ] || fail "render alpha never died holding a frame in 5 attempts"
echo "killed alpha while it held $(basename "$held")"
wait $b || { cat "$out/${dir}_beta.log"; fail "render beta"; }
cat "$out/${dir}_alpha.log" "$out/${dir}_beta.log"
frame=$(basename "$held" .claim | sed 's/^ball_0*//; s/^$/0/')
grep -q "frame $frame: took over a dead claim (host alpha, pid $a, .*: not refreshed for [0-9]* s, the limit is 5 s)" \
  "$out/${dir}_beta.log" || fail "render beta did not take frame $frame over"
same_frames "$work/shared/$dir"
[ -z "$(leftovers "$work/shared/$dir" | grep -v '\.alpha-[0-9]*\.tmp$')" ] \
  || fail "left in the folder: $(leftovers "$work/shared/$dir")"
echo "2: frame $frame taken over from the killed render, frames identical"
echo "ok"
