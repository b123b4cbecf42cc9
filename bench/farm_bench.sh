#!/usr/bin/env bash
# The farm on one machine: BALL, 60 frames at 320x240, rendered by one process (all cores) and
# through `steadylight submit` on a one-node Slurm cluster started here (tests/farm/local_slurm.sh,
# as root) with 2 workers of 1 CPU each. Prints both wall times and where the Slurm path's
# extra time goes: per chunk, the set-up a task does outside its frames (scene, acceleration
# structures, static cache load), and the scheduling and waiting left over.
#   bench/farm_bench.sh [BUILD_DIR] [--chunk N] [--frames N] [--size WxH]
set -euo pipefail
source=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$source/build}
[ $# -gt 0 ] && shift
chunk=10 frames=60 size=320x240
while [ $# -gt 0 ]; do
  case $1 in
    --chunk) chunk=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done
binary=$build/steadylight
scene=$source/scenes/ball.json
options=(--size "$size" --frames "0-$((frames - 1))")
work=$(mktemp -d /tmp/steadylight-farm-bench.XXXXXX)
chmod 755 "$work"  # munged runs as the munge user and needs to reach the cluster folder inside
cluster=$work/cluster
trap 'bash "$source/tests/farm/local_slurm.sh" stop "$cluster"; rm -rf "$work"' EXIT
bash "$source/tests/farm/local_slurm.sh" start "$cluster" > "$work/cluster.log" 2>&1 || { cat "$work/cluster.log"; exit 1; }
export SLURM_CONF=$cluster/slurm.conf
now() { date +%s.%N; }
seconds_of() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }

echo "BALL, $frames frames at $size, $(nproc) cores; $(date -u +%Y-%m-%dT%H:%MZ)"
start=$(now)
"$binary" render "$scene" "${options[@]}" --out "$work/one" --no-progress > "$work/one.log" 2>&1
one=$(seconds_of "$start" "$(now)")
printf "%-52s %8s s\n" "one machine: 1 process, $(nproc) threads" "$one"

start=$(now)
"$binary" submit "$scene" "${options[@]}" --chunk "$chunk" --cpus-per-task 1 --out "$work/farm" > "$work/submit.log"
ids=$(sed -n 's/^submitted jobs \([0-9,]*\) .*/\1/p' "$work/submit.log")
while [ -n "$(squeue --noheader --jobs "$ids")" ]; do sleep 0.2; done
farm=$(seconds_of "$start" "$(now)")
for id in ${ids//,/ }; do
  state=$(scontrol show job "$id" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -n 1)
  [ "$state" = COMPLETED ] || { echo "job $id: $state"; tail -n 20 "$work"/farm/slurm/*.log; exit 1; }
done
for file in "$work"/farm/ball_*.exr "$work"/farm/ball_*.png; do
  cmp -s "$file" "$work/one/$(basename "$file")" || { echo "$(basename "$file") differs from the one-machine render"; exit 1; }
done
printf "%-52s %8s s  (submit to the finishing job's end; frames identical)\n" \
  "Slurm: 2 workers x 1 CPU, chunks of $chunk" "$farm"

# The task logs: "frame N  X s" per frame, "... written ... in S s" per task, the cache load.
awk '
  /records computed in/ { for (i = 1; i <= NF; i++) if ($i == "in") { bake = $(i + 1); break } }
  /^\[.*\] \[info\] frame +[0-9]+ +[0-9.]+ s/ { frames_s += $5 }
  /frame\(s\) written/ { tasks++; for (i = 1; i <= NF; i++) if ($i == "in") last = $(i + 1); task_s += last }
  /records loaded from/ { loads++; load_s += $(NF - 1) }
  END {
    printf "  %-50s %8.1f s\n", "bake job: static pass (1 thread)", bake
    printf "  %-50s %8.1f s\n", "frames, summed over the " tasks " tasks (1 thread each)", frames_s
    printf "  %-50s %8.2f s\n", "per chunk: set-up outside its frames", (task_s - frames_s) / tasks
    printf "  %-50s %8.3f s\n", "  of which loading the static cache", load_s / loads
    printf "%s %.1f %.1f %d\n", "SUMS", bake, task_s, tasks > "/dev/stderr"
  }' "$work"/farm/slurm/bake_0_*.log "$work"/farm/slurm/render_0_*.log 2> "$work/sums"
read -r _ bake tasks_s tasks < "$work/sums"
awk -v farm="$farm" -v bake="$bake" -v tasks_s="$tasks_s" -v tasks="$tasks" 'BEGIN {
  busy = bake + tasks_s / 2
  printf "  %-50s %8.1f s  (%.2f s per chunk)\n", "scheduling, waiting, finishing job: wall - busy", farm - busy, (farm - busy) / tasks
}'
