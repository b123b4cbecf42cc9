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
source "$source/tests/farm/slurm_support.sh"

rm -rf "$out"
mkdir -p "$out"
start_cluster

started=$SECONDS
render_reference

# sbatch's refusal is a clear error.
status=0
"$binary" submit "$scene" "${options[@]}" --partition nosuch --out "$out/refused" > "$out/refused.log" 2>&1 || status=$?
cat "$out/refused.log"
[ $status -eq 1 ] && grep -q "bake_0.sh: sbatch refused the job (exit status 1): sbatch: error: invalid partition specified: nosuch" \
  "$out/refused.log" || fail "an unknown partition: exit status $status"

# 1. A whole submission.
read -r -a jobs <<< "$(submit "$out/farm" "$out/submit1.log" --chunk 3)"
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
read -r -a jobs <<< "$(submit "$out/again" "$out/submit2.log" --chunk 3)"
scancel "${jobs[1]}_1"  # frames 3-5; the array still waits for its bake
wait_for "${jobs[@]}"
[ "$(job_state "${jobs[2]}")" = FAILED ] || fail "the finishing job after a cancelled task: $(job_state "${jobs[2]}")"
grep -q "3 of the 12 selected frame(s) are not complete: 3-5" "$out"/again/slurm/finish_"${jobs[2]}".log \
  || { cat "$out"/again/slurm/finish_"${jobs[2]}".log; fail "the finishing job does not name the missing frames"; }
before=$(stat -c '%n %Y %s' "$out"/again/ball_00*.manifest.json "$out/again/ball.irrcache")
read -r -a jobs <<< "$(submit "$out/again" "$out/submit3.log" --chunk 3)"
grep -q "3 of 12 frame(s) to render (9 complete), in 1 chunk(s) of at most 3 over 1 segment(s); 0 static cache(s) to bake" \
  "$out/submit3.log" || fail "the resubmission's plan"
[ ${#jobs[@]} -eq 2 ] || fail "expected an array and a finishing job, got: ${jobs[*]}"
wait_for "${jobs[@]}"
for job in "${jobs[@]}"; do [ "$(job_state "$job")" = COMPLETED ] || fail "resubmitted job $job: $(job_state "$job")"; done
grep -q "3 frame(s) written, 0 complete ones skipped" "$out"/again/slurm/render_0_"${jobs[0]}"_0.log || fail "the task's frames"
[ "$before" = "$(stat -c '%n %Y %s' $(awk '{print $1}' <<< "$before"))" ] || fail "files of complete frames or the cache changed"
same_frames "$out/again"
echo "ok: Slurm farm test passed in $((SECONDS - started)) s"
