# Sourced by the tests that run `steadylight submit` on a real Slurm (tests/farm/slurm_test.sh,
# tests/farm/slurm_faults.sh). The test sets binary, source, out, scene and options (the render
# options of every run) first; this file gives it:
#   fail MESSAGE              prints FAIL: MESSAGE and exits 1
#   start_cluster             a one-node cluster (tests/farm/local_slurm.sh) in a short temporary
#                             folder, stopped on exit (after the test's own `cleanup`, if it
#                             defines one); exports SLURM_CONF. Skips (77) without slurm-wlm,
#                             munge or root, except under CI=true, where it fails.
#   render_reference          the one-machine render of the frames into $out/one
#   submit DIR LOG [OPTION...] steadylight submit into DIR (more submit options after the
#                             render options), its output in LOG; prints the job ids
#   wait_for ID...            until Slurm lists none of the jobs as pending or running
#   job_state ID              PENDING, RUNNING, COMPLETED, FAILED, CANCELLED...
#   same_frames DIR           every EXR and PNG of $out/one equals DIR's byte for byte
source "$source/tests/support/skip.sh"
fail() { echo "FAIL: $*"; exit 1; }

start_cluster() {
  # A short path: munge's socket lives in it.
  cluster=$(mktemp -d /tmp/steadylight-slurm.XXXXXX)
  trap '[ "$(type -t cleanup)" != function ] || cleanup
        bash "$source/tests/farm/local_slurm.sh" stop "$cluster"; rm -rf "$cluster"' EXIT
  local status=0
  bash "$source/tests/farm/local_slurm.sh" start "$cluster" > "$out/cluster.log" 2>&1 || status=$?
  cat "$out/cluster.log"
  if [ $status -eq 77 ]; then
    skip_without_tool "no one-node Slurm cluster here: it needs slurm-wlm and munge (scripts/setup.sh) and root"
  fi
  [ $status -eq 0 ] || fail "the local Slurm cluster did not start"
  export SLURM_CONF=$cluster/slurm.conf
}

render_reference() {
  "$binary" render "$scene" "${options[@]}" --out "$out/one" --no-progress > "$out/one.log" 2>&1 \
    || { cat "$out/one.log"; fail "one-machine render"; }
}

submit() {
  local dir=$1 log=$2
  shift 2
  "$binary" submit "$scene" "${options[@]}" "$@" --out "$dir" > "$log" 2>&1 || { cat "$log"; fail "submit into $dir"; }
  cat "$log" >&2
  sed -n 's/^submitted jobs \([0-9,]*\) .*/\1/p' "$log" | tr , ' '
}

wait_for() {
  for _ in $(seq 2400); do
    [ -z "$(squeue --noheader --jobs "$(IFS=,; echo "$*")" 2>/dev/null)" ] && return 0
    sleep 0.25
  done
  squeue; fail "jobs $* still queued after 10 minutes"
}

job_state() { scontrol show job "$1" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -n 1; }

same_frames() {
  local file
  for file in "$out"/one/*.exr "$out"/one/*.png; do
    cmp "$file" "$1/$(basename "$file")" || fail "$1/$(basename "$file") differs from the one-machine render"
  done
}
