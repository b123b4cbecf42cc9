#!/usr/bin/env bash
# `steadylight submit` on a real Slurm: a one-node cluster started on this machine
# (tests/farm/local_slurm.sh, as root), BALL at 80x60, 12 frames in chunks of 3.
# 0. An unknown partition is refused with sbatch's message, exit status 1.
# 1. The farm's frames are byte-identical to a one-machine render, and the finishing job
#    completes (report written).
# 2. A second submission with one array task cancelled: its finishing job fails naming the
#    missing frames; submitting again bakes nothing, renders only those frames (the others'
#    files untouched), and the frames are then identical to the one-machine render.
# Skipped (77) without slurm-wlm and munge or without root, except under CI=true, where it fails.
#   slurm_test.sh BINARY SOURCE_DIR OUT_DIR
set -euo pipefail
binary=$1 source=$2 out=$3
scene=$source/scenes/ball.json
options=(--size 80x60 --frames 0-11 --spp 4 --photons 20000 --caustic-photons 2000 --gather-samples 64)
fail() { echo "FAIL: $*"; exit 1; }
source "$source/tests/support/skip.sh"

rm -rf "$out"
mkdir -p "$out"
# A short path: munge's socket lives in it.
cluster=$(mktemp -d /tmp/steadylight-slurm.XXXXXX)
trap 'bash "$source/tests/farm/local_slurm.sh" stop "$cluster"; rm -rf "$cluster"' EXIT
status=0
bash "$source/tests/farm/local_slurm.sh" start "$cluster" > "$out/cluster.log" 2>&1 || status=$?
cat "$out/cluster.log"
if [ $status -eq 77 ]; then
  skip_without_tool "no one-node Slurm cluster here: it needs slurm-wlm and munge (scripts/setup.sh) and root"
fi
[ $status -eq 0 ] || fail "the local Slurm cluster did not start"
export SLURM_CONF=$cluster/slurm.conf

wait_for() {  # wait_for IDS...: until Slurm lists none of the jobs as pending or running
  for _ in $(seq 600); do
    [ -z "$(squeue --noheader --jobs "$(IFS=,; echo "$*")" 2>/dev/null)" ] && return 0
    sleep 1
  done
  squeue; fail "jobs $* still queued after 10 minutes"
}
job_state() { scontrol show job "$1" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -n 1; }
submit() {  # submit DIR LOG: prints the job ids
  "$binary" submit "$scene" "${options[@]}" --chunk 3 --out "$1" > "$2" 2>&1 || { cat "$2"; fail "submit into $1"; }
  cat "$2" >&2
  sed -n 's/^submitted jobs \([0-9,]*\) .*/\1/p' "$2" | tr , ' '
}
same_frames() {  # same_frames DIR: every frame's EXR and PNG as in the one-machine render
  for frame in $(seq 0 11); do
    for ext in exr png; do
      file=$(printf "ball_%04d.%s" "$frame" "$ext")
      cmp "$out/one/$file" "$1/$file" || fail "$1/$file differs from the one-machine render"
    done
  done
}

started=$SECONDS
"$binary" render "$scene" "${options[@]}" --out "$out/one" --no-progress > "$out/one.log" 2>&1 \
  || { cat "$out/one.log"; fail "one-machine render"; }

# sbatch's refusal is a clear error.
status=0
"$binary" submit "$scene" "${options[@]}" --partition nosuch --out "$out/refused" > "$out/refused.log" 2>&1 || status=$?
cat "$out/refused.log"
[ $status -eq 1 ] && grep -q "bake_0.sh: sbatch refused the job (exit status 1): sbatch: error: invalid partition specified: nosuch" \
  "$out/refused.log" || fail "an unknown partition: exit status $status"

# 1. A whole submission.
read -r -a jobs <<< "$(submit "$out/farm" "$out/submit1.log")"
[ ${#jobs[@]} -eq 3 ] || fail "expected a bake, an array and a finishing job, got: ${jobs[*]}"
grep -q "12 of 12 frame(s) to render (0 complete), in 4 chunk(s) of at most 3 over 1 segment(s); 1 static cache(s) to bake" \
  "$out/submit1.log" || fail "submit's plan"
grep -q -- "--dependency=afterok:${jobs[0]} --kill-on-invalid-dep=yes" "$out/submit1.log" || fail "the array does not depend on the bake"
grep -q -- "--dependency=afterany:${jobs[1]} " "$out/submit1.log" || fail "the finishing job does not wait for the array"
wait_for "${jobs[@]}"
tail -n 3 "$out"/farm/slurm/*.log
for job in "${jobs[@]}"; do [ "$(job_state "$job")" = COMPLETED ] || fail "job $job: $(job_state "$job")"; done
grep -q "records loaded from" "$out"/farm/slurm/render_0_"${jobs[1]}"_0.log || fail "task 0 did not load the baked cache"
[ -s "$out/farm/report.html" ] || fail "no report"
same_frames "$out/farm"
echo "farm: 12 frames identical to the one-machine render ($((SECONDS - started)) s so far)"

# 2. One task cancelled, then resubmitted.
read -r -a jobs <<< "$(submit "$out/again" "$out/submit2.log")"
scancel "${jobs[1]}_1"  # frames 3-5; the array still waits for its bake
wait_for "${jobs[@]}"
[ "$(job_state "${jobs[2]}")" = FAILED ] || fail "the finishing job after a cancelled task: $(job_state "${jobs[2]}")"
grep -q "3 of the 12 selected frame(s) are not complete: 3-5" "$out"/again/slurm/finish_"${jobs[2]}".log \
  || { cat "$out"/again/slurm/finish_"${jobs[2]}".log; fail "the finishing job does not name the missing frames"; }
before=$(stat -c '%n %Y %s' "$out"/again/ball_00*.manifest.json "$out/again/ball.irrcache")
read -r -a jobs <<< "$(submit "$out/again" "$out/submit3.log")"
grep -q "3 of 12 frame(s) to render (9 complete), in 1 chunk(s) of at most 3 over 1 segment(s); 0 static cache(s) to bake" \
  "$out/submit3.log" || fail "the resubmission's plan"
[ ${#jobs[@]} -eq 2 ] || fail "expected an array and a finishing job, got: ${jobs[*]}"
wait_for "${jobs[@]}"
for job in "${jobs[@]}"; do [ "$(job_state "$job")" = COMPLETED ] || fail "resubmitted job $job: $(job_state "$job")"; done
grep -q "3 frame(s) written, 0 complete ones skipped" "$out"/again/slurm/render_0_"${jobs[0]}"_0.log || fail "the task's frames"
[ "$before" = "$(stat -c '%n %Y %s' $(awk '{print $1}' <<< "$before"))" ] || fail "files of complete frames or the cache changed"
same_frames "$out/again"
echo "ok: Slurm farm test passed in $((SECONDS - started)) s"
