#!/usr/bin/env bash
# The farm under faults, on a real Slurm: the one-node cluster of tests/farm/local_slurm.sh (as
# root, 2 CPUs, tasks of 1 CPU), BALL at 80x60, 12 frames, one cluster and one one-machine
# render shared by the cases. In each case the frames end byte-identical (EXR and PNG) to the
# one-machine render, and the finishing job's log says what is missing, if anything.
# To stop a task mid-chunk at the same point in every run, its jobs are submitted held
# (SBATCH_HOLD), the bake released, the array released while the test holds the folder's lock
# (a lock file naming this shell: the task waits at it before any frame), and the task's process
# stopped (SIGSTOP, seen to hold in every thread before the lock goes, and sent again whenever it
# is found running outside a slice) and then run in slices of about a millisecond until one frame
# of its chunk is complete and it is inside the next one (a frame at this size takes 10-30 ms, its
# write a few: longer slices can step over that moment and past the chunk's end).
# 1. A task killed mid-chunk (SIGKILL of its steadylight process, which leaves its claim): the
#    finishing job fails naming the frames the task did not write; the resubmission renders only
#    those, takes the dead claim over at once (its pid on this host is gone) and removes the
#    frame's stale .partial file (one is put there when the kill did not leave one, as a kill
#    while the frame is written does).
# 2. The node set DOWN while a task is inside a frame: Slurm requeues the task (JobRequeue=1,
#    the default, and submit passes no --no-requeue) and ends its run with SIGTERM, on which
#    steadylight drops the frame in progress and exits 130; the requeued task waits for its
#    BeginTime, 120 s later (the test brings it forward), and Slurm truncates its log when it
#    runs again. The node answers, so ReturnToService=2 returns it to service at once (then
#    `state=resume` is refused: nothing to resume); it is resumed if it is still down. The
#    finishing job waits meanwhile (a requeue does not end the array), the second run skips
#    the complete frames and renders the rest, and the finishing job finds all complete.
# 3. A resubmission while the earlier submission's jobs are all pending (the node drained):
#    submit cancels them (it prints the scancel line, and nothing is said to be still running),
#    they end CANCELLED without running, and the new jobs render every frame once.
# 4. A resubmission while a task of the earlier submission runs (stopped inside a frame): its
#    pending finishing job is cancelled, the new finishing job waits for the running array too
#    (afterany on both) and stays pending; the new task leaves the frame the old one holds and
#    waits for it at the end; once the old task goes on, it renders that frame and the waiting
#    task finds it complete; every frame is rendered once.
# Skipped (77) without slurm-wlm and munge or without root, except under CI=true, where it fails.
#   slurm_faults.sh BINARY SOURCE_DIR OUT_DIR
set -euo pipefail
binary=$1 source=$2 out=$3
scene=$source/scenes/ball.json
options=(--size 80x60 --frames 0-11 --spp 4 --photons 20000 --caustic-photons 2000 --gather-samples 64)
source "$source/tests/farm/slurm_support.sh"
node=$(hostname -s)
caught=()  # steadylight processes this test stopped: ended if the test stops early

cleanup() {  # on exit, before the cluster stops: nothing of this test left running
  local pid
  for pid in "${caught[@]}"; do
    tr '\0' ' ' < "/proc/$pid/cmdline" 2>/dev/null | grep -q -- "--out $out/" && kill -KILL "$pid"
  done
  [ -n "${SLURM_CONF:-}" ] || return 0
  scancel --quiet --user "$(id -un)" 2>/dev/null || true
  for _ in $(seq 60); do [ -z "$(squeue --noheader 2>/dev/null)" ] && break; sleep 0.25; done
}

# The frame numbers of the "frame N ... s DIR/ball_N.exr" lines of every log in DIR/slurm: one
# line per frame a process wrote.
rendered_frames() {
  cat "$1"/slurm/*.log | sed -n 's/.*\] frame *\([0-9]*\) .* s  .*\.exr  (written in.*/\1/p' | sort -n | tr '\n' ' '
}
every_frame_once() {
  [ "$(rendered_frames "$1")" = "$(seq 0 11 | tr '\n' ' ')" ] \
    || fail "$1: the frames written, by their logs: $(rendered_frames "$1") (each of 0-11 once expected)"
}
finished_complete() {  # finished_complete DIR FINISH_JOB: the finishing job found every frame complete, as in $out/one
  [ "$(job_state "$2")" = COMPLETED ] || { cat "$1/slurm/finish_$2.log"; fail "finishing job $2: $(job_state "$2")"; }
  grep -q "all 12 selected frame(s) are complete" "$1/slurm/finish_$2.log" || fail "finishing job $2's log"
  [ -s "$1/report.html" ] || fail "$1: no report"
  ! ls "$1" | grep -E '\.(claim|partial)$' || fail "$1: claims or temporary files left"
  same_frames "$1"
}
wait_state() {  # wait_state JOB STATE
  for _ in $(seq 400); do [ "$(job_state "$1")" = "$2" ] && return 0; sleep 0.05; done
  fail "job $1 is $(job_state "$1"), not $2"
}

thread_states() {  # thread_states PID: the state letter of each thread of the process (none once it ended)
  local stat line states=
  for stat in /proc/"$1"/task/*/stat; do
    read -r line < "$stat" 2>/dev/null || continue
    line=${line##*) }  # the field after the command's name, which may hold spaces and parentheses
    states+=${line%% *}
  done
  echo "$states"
}
all_stopped() { [ -n "$1" ] && [ -z "${1//T/}" ]; }  # all_stopped STATES: every thread stopped
stopped() { all_stopped "$(thread_states "$1")"; }   # stopped PID
# Stops PID and waits until every thread of it is stopped, sending SIGSTOP again while one is not
# (a SIGCONT from elsewhere must not let the task run through its chunk unseen). Fails naming the
# process and its threads' states if it does not stop.
stop_task() {  # stop_task PID
  for _ in $(seq 400); do
    kill -STOP "$1" 2>/dev/null || fail "the task (pid $1) ended before it was stopped"
    stopped "$1" && return 0
    sleep 0.005
  done
  fail "the task (pid $1) does not stop: $(tr '\0' ' ' < "/proc/$1/cmdline"), threads $(thread_states "$1")"
}

# Runs the stopped process PID in slices of about 1 ms until a frame of FIRST..LAST is complete and
# the one claim of the chunk is another's, not complete (the task is inside that frame, its
# earlier frames written and their claims gone), with DIR's lock free; leaves it stopped there.
# Sets inside (that frame).
step_to_mid_chunk() {  # step_to_mid_chunk PID DIR FIRST LAST
  local frame base written claims seen= states=
  for _ in $(seq 20000); do
    kill -0 "$1" 2>/dev/null ||
      fail "the task (pid $1) ended before it was stopped inside its chunk; last seen:$seen; its threads last:$states"
    states=$(thread_states "$1")
    if all_stopped "$states"; then
      written=0 claims=() seen=
      for frame in $(seq "$3" "$4"); do
        base=$(printf "%s/ball_%04d" "$2" "$frame")
        [ -e "$base.manifest.json" ] && written=1 seen+=" $frame complete"
        [ -e "$base.claim" ] && claims+=("$frame") seen+=" $frame claimed"
      done
      inside=${claims[0]:-}
      [ $written = 1 ] && [ ${#claims[@]} = 1 ] && [ ! -e "$(printf "%s/ball_%04d.manifest.json" "$2" "$inside")" ] &&
        [ ! -e "$2/.steadylight.lock" ] && return 0
      kill -CONT "$1"
      sleep 0.001
    fi
    # Again while it has not stopped yet: a SIGCONT from elsewhere must not let it run on.
    kill -STOP "$1" 2>/dev/null || fail "the task (pid $1) ended within a slice, past its chunk's middle; last seen:$seen"
    sleep 0.002
  done
  fail "the task (pid $1) did not reach the middle of its chunk; last seen:$seen"
}

# Submits into DIR held (SBATCH_HOLD), runs the bake, then releases the array and its finishing
# job while holding DIR's lock, and stops the task whose steadylight process renders FIRST-LAST:
# it waits at the lock before rendering anything. Then steps it to the middle of that chunk
# (step_to_mid_chunk). Sets jobs (bake, array, finishing job), pid and inside.
submit_stopped_mid_chunk() {  # submit_stopped_mid_chunk DIR LOG FIRST LAST [SUBMIT OPTION...]
  local dir=$1 log=$2 first=$3 last=$4
  shift 4
  read -r -a jobs <<< "$(SBATCH_HOLD=1 submit "$dir" "$log" "$@")"
  [ ${#jobs[@]} -eq 3 ] || fail "expected a bake, an array and a finishing job, got: ${jobs[*]}"
  scontrol release "${jobs[0]}"
  wait_for "${jobs[0]}"
  [ "$(job_state "${jobs[0]}")" = COMPLETED ] || fail "bake ${jobs[0]}: $(job_state "${jobs[0]}")"
  # The folder's lock, as a live process of this host holds it (src/steadylight/base/lock_file.h).
  printf '{"host":"%s","pid":%d,"time":"now"}\n' "$(hostname)" $$ > "$dir/.steadylight.lock"
  scontrol release "${jobs[1]}" "${jobs[2]}"
  pid=
  for _ in $(seq 600); do
    pid=$(pgrep -f -- "--out $dir --threads 1 --frames $first-$last --require-cache" || true)
    [ -n "$pid" ] && break
    sleep 0.05
  done
  [ -n "$pid" ] || { squeue; fail "no task of array ${jobs[1]} renders frames $first-$last"; }
  caught+=("$pid")
  stop_task "$pid"
  rm "$dir/.steadylight.lock"
  step_to_mid_chunk "$pid" "$dir" "$first" "$last"
}

rm -rf "$out"
mkdir -p "$out"
start_cluster
started=$SECONDS
render_reference

# 1. A task killed mid-chunk, then resubmitted.
dir=$out/killed
submit_stopped_mid_chunk "$dir" "$out/killed_submit1.log" 3 5 --chunk 3
missing=$(seq "$inside" 5 | tr '\n' ' ')
kill -KILL "$pid"
wait_for "${jobs[@]}"
[ "$(job_state "${jobs[1]}_1")" = FAILED ] || fail "the killed task: $(job_state "${jobs[1]}_1")"
[ "$(job_state "${jobs[2]}")" = FAILED ] || fail "the finishing job after a killed task: $(job_state "${jobs[2]}")"
list=$(awk '{print NF == 1 ? $1 : $1 "-" $NF}' <<< "$missing")
count=$(wc -w <<< "$missing")
grep -q "$count of the 12 selected frame(s) are not complete: $list\$" "$dir/slurm/finish_${jobs[2]}.log" \
  || { cat "$dir/slurm/finish_${jobs[2]}.log"; fail "the finishing job does not name the missing frames $list"; }
partial=$(printf "ball_%04d.exr.partial" "$inside")
claim=$(printf "ball_%04d.claim" "$inside")
[ "$(cd "$dir" && echo *.claim)" = "$claim" ] || fail "claims left by the killed task: $(cd "$dir" && echo *.claim), not only $claim"
grep -q "\"pid\":$pid," "$dir/$claim" || fail "the killed task's claim of frame $inside"
left_partials=$(cd "$dir" && ls | grep '\.partial$' | tr '\n' ' ' || true)
[ -n "$left_partials" ] || { : > "$dir/$partial"; left_partials="$partial (put there)"; }
read -r -a jobs <<< "$(submit "$dir" "$out/killed_submit2.log" --chunk 3)"
grep -q "$count of 12 frame(s) to render ($((12 - count)) complete), in 1 chunk(s) of at most 3 over 1 segment(s); 0 static cache(s) to bake" \
  "$out/killed_submit2.log" || fail "the resubmission's plan"
wait_for "${jobs[@]}"
task_log=$dir/slurm/render_0_${jobs[0]}_0.log
[ "$(job_state "${jobs[0]}")" = COMPLETED ] || { cat "$task_log"; fail "the resubmitted task: $(job_state "${jobs[0]}")"; }
grep -q "frame $inside: took over a dead claim (host $node, pid $pid, refreshed [0-9]* s ago: its process $pid on this host is gone)" \
  "$task_log" || { cat "$task_log"; fail "the dead claim of frame $inside was not taken over"; }
for name in ${left_partials% (put there)}; do
  grep -q "removed the stale $name" "$task_log" || { cat "$task_log"; fail "$name was not removed"; }
done
grep -q "$count frame(s) written, 0 complete ones skipped" "$task_log" || fail "the resubmitted task's frames"
finished_complete "$dir" "${jobs[1]}"
every_frame_once "$dir"
echo "1. killed in frame $inside: frames $list missing, stale $left_partials removed, then rendered by the resubmission ($((SECONDS - started)) s so far)"

# 2. The node set down while a task is inside a frame, and resumed.
dir=$out/down
submit_stopped_mid_chunk "$dir" "$out/down_submit.log" 0 11 --chunk 12
scontrol update nodename="$node" state=down reason=slurm_faults
for _ in $(seq 400); do kill -0 "$pid" 2>/dev/null || break; sleep 0.05; done
! kill -0 "$pid" 2>/dev/null || fail "the task (pid $pid) still runs after the node went down"
node_state=$(sinfo --noheader --nodes "$node" --format %t)
done_before=$(ls "$dir"/*.manifest.json | wc -l)
task=${jobs[1]}_0
grep -q "requeue job JobId=${task}([0-9]*) due to failure of node $node" "$cluster/slurmctld.log" \
  || fail "slurmctld did not requeue $task"
# Requeued: pending until its BeginTime; its first run's log is kept before the second truncates it.
wait_state "$task" PENDING
cp "$dir/slurm/render_0_${jobs[1]}_0.log" "$out/down_first_run.log"
scontrol show job "$task" | grep -q "Restarts=1" || fail "task $task was not requeued"
scontrol show job "$task" | grep -q "Reason=BeginTime" || fail "the requeued task $task does not wait for its BeginTime"
begin=$(scontrol show job "$task" | sed -n 's/.* StartTime=\([^ ]*\).*/\1/p' | head -n 1)
delay=$(( $(date -d "$begin" +%s) - $(date +%s) ))
grep -q "DUE TO NODE FAILURE" "$out/down_first_run.log" || fail "the first run's log does not say the node failed"
grep -q "stopping; the frame in progress is dropped" "$out/down_first_run.log" \
  || { cat "$out/down_first_run.log"; fail "the task was not stopped by SIGTERM"; }
[ "$(job_state "${jobs[2]}")" = PENDING ] || fail "the finishing job during the requeue: $(job_state "${jobs[2]}")"
! ls "$dir" | grep -E '\.(claim|partial)$' || fail "the interrupted task left claims or temporary files"
if sinfo --noheader --nodes "$node" --format %t | grep -q down; then
  scontrol update nodename="$node" state=resume
fi
scontrol update jobid="$task" starttime=now
wait_for "${jobs[@]}"
task_log=$dir/slurm/render_0_${jobs[1]}_0.log
[ "$(job_state "$task")" = COMPLETED ] || { cat "$task_log"; fail "the requeued task: $(job_state "$task")"; }
grep -q "$((12 - done_before)) frame(s) written, $done_before complete ones skipped" "$task_log" \
  || { cat "$task_log"; fail "the requeued task did not render only the frames left"; }
finished_complete "$dir" "${jobs[2]}"
echo "2. node down in frame $inside (node then $node_state): task requeued to start ${delay} s later, brought forward; its second run rendered frames $inside-11 ($((SECONDS - started)) s so far)"

# 3. A resubmission while every job of the earlier one is pending.
dir=$out/pending
scontrol update nodename="$node" state=drain reason=slurm_faults
read -r -a earlier <<< "$(submit "$dir" "$out/pending_submit1.log" --chunk 3)"
for job in "${earlier[@]}"; do [ "$(job_state "$job")" = PENDING ] || fail "job $job on a drained node: $(job_state "$job")"; done
read -r -a jobs <<< "$(submit "$dir" "$out/pending_submit2.log" --chunk 3)"
grep -q "^ran: scancel --state=PENDING ${earlier[*]}\$" "$out/pending_submit2.log" || fail "submit did not cancel the pending jobs"
! grep -q "still running" "$out/pending_submit2.log" || fail "pending jobs taken for running ones"
for job in "${earlier[@]}"; do [ "$(job_state "$job")" = CANCELLED ] || fail "earlier job $job: $(job_state "$job")"; done
scontrol update nodename="$node" state=resume
wait_for "${jobs[@]}"
for job in "${jobs[@]}"; do [ "$(job_state "$job")" = COMPLETED ] || fail "job $job: $(job_state "$job")"; done
! ls "$dir/slurm/bake_0_${earlier[0]}.log" "$dir/slurm/render_0_${earlier[1]}"_*.log "$dir/slurm/finish_${earlier[2]}.log" 2>/dev/null \
  || fail "a cancelled job ran"
finished_complete "$dir" "${jobs[2]}"
every_frame_once "$dir"
echo "3. pending jobs ${earlier[*]} cancelled by the resubmission ($((SECONDS - started)) s so far)"

# 4. A resubmission while a task of the earlier one runs.
dir=$out/running
submit_stopped_mid_chunk "$dir" "$out/running_submit1.log" 0 11 --chunk 12
earlier=("${jobs[@]}")
read -r -a jobs <<< "$(submit "$dir" "$out/running_submit2.log" --chunk 3)"
[ ${#jobs[@]} -eq 2 ] || fail "expected an array and a finishing job, got: ${jobs[*]}"
grep -q "^still running from the earlier submission (the finishing job waits for them): ${earlier[1]}\$" \
  "$out/running_submit2.log" || fail "submit does not wait for the running array"
grep -q -- "--dependency=afterany:${earlier[1]}:${jobs[0]} " "$out/running_submit2.log" \
  || fail "the finishing job does not wait for both arrays"
[ "$(job_state "${earlier[2]}")" = CANCELLED ] || fail "the earlier finishing job: $(job_state "${earlier[2]}")"
# The new task that meets frame $inside leaves it and, its other frames done, waits for it.
new_logs=("$dir"/slurm/render_0_"${jobs[0]}"_*.log)
for _ in $(seq 1200); do
  new_logs=("$dir"/slurm/render_0_"${jobs[0]}"_*.log)
  grep -qs "waiting for frame(s) .*claimed by other processes" "${new_logs[@]}" && break
  sleep 0.1
done
waiting_log=$(grep -ls "waiting for frame(s) .*claimed by other processes" "${new_logs[@]}") \
  || { squeue; fail "no new task waits for frame $inside"; }
grep -q "frame $inside: claimed by another process (host $node, pid $pid, refreshed [0-9]* s ago), left to it for now" \
  "$waiting_log" || { cat "$waiting_log"; fail "the waiting task did not leave frame $inside to the running one"; }
[ "$(job_state "${earlier[1]}")" = RUNNING ] || fail "the earlier task: $(job_state "${earlier[1]}")"
[ "$(job_state "${jobs[1]}")" = PENDING ] || fail "the finishing job while a task runs: $(job_state "${jobs[1]}")"
kill -CONT "$pid"
wait_for "${earlier[1]}" "${jobs[@]}"
[ "$(job_state "${earlier[1]}")" = COMPLETED ] || fail "the earlier task: $(job_state "${earlier[1]}")"
grep -q "frame $inside: completed by another process meanwhile, skipped" "$waiting_log" \
  || { cat "$waiting_log"; fail "the waiting task did not find frame $inside complete"; }
for job in "${jobs[@]}"; do [ "$(job_state "$job")" = COMPLETED ] || fail "job $job: $(job_state "$job")"; done
finished_complete "$dir" "${jobs[1]}"
every_frame_once "$dir"
echo "4. the finishing job waited for the earlier task inside frame $inside ($((SECONDS - started)) s so far)"
echo "ok: Slurm fault tests passed in $((SECONDS - started)) s"
