#!/usr/bin/env bash
# Runs a benchmark and writes what it printed to docs/results/<BENCHMARK>.md with the machine, the
# date, the commit and the command, so that figures in the documentation are regenerated, never
# copied by hand (docs/benchmarks.md). Commit the file with the change it measures.
#   bash bench/results.sh [--as NAME] BENCHMARK [ARGS...]
# BENCHMARK is a program of build/ (ray_tracer_bench, quality_bench, ...) or a script
# bench/BENCHMARK.sh (methods_bench, reuse_bench, farm_bench). --as writes docs/results/<NAME>.md
# instead: the figures of one run of a benchmark over part of its work, kept beside the full run's.
set -euo pipefail
cd "$(dirname "$0")/.."
file_name=
if [ "${1:-}" = --as ]; then
  file_name=${2:?usage: bash bench/results.sh [--as NAME] BENCHMARK [ARGS...]}
  shift 2
fi
name=${1:?usage: bash bench/results.sh [--as NAME] BENCHMARK [ARGS...]}
shift
file_name=${file_name:-$name}
if [ -f "bench/$name.sh" ]; then
  command=(bash "bench/$name.sh" "$@")
elif [ -f "bench/$name.cpp" ]; then
  [ -x "build/$name" ] || bash scripts/build.sh
  command=("build/$name" "$@")
else
  echo "results.sh: no benchmark named $name (bench/$name.sh or bench/$name.cpp)" >&2
  exit 1
fi
commit=$(git describe --always --dirty 2>/dev/null || echo unknown)
cpu=$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //' || echo unknown)
load=$(cut -d' ' -f1-3 /proc/loadavg)
started=$(date -u '+%Y-%m-%d %H:%M UTC')
output=$(mktemp)
trap 'rm -f "$output"' EXIT
"${command[@]}" | tee "$output"
sed -i 's/\x1b\[[0-9;]*m//g' "$output"  # terminal colours (Google Benchmark's) left out of the file
mkdir -p docs/results
file=docs/results/$file_name.md
as=
[ "$file_name" = "$name" ] || as="--as $file_name "
{
  echo "# $file_name"
  echo
  echo "Written by \`bash bench/results.sh $as$name${*:+ $*}\` (docs/benchmarks.md says what it measures)."
  echo
  echo "- date: $started"
  echo "- commit: $commit"
  echo "- machine: $cpu, $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2 / 1048576}' /proc/meminfo), load average at the start $load"
  echo
  echo '```'
  cat "$output"
  echo '```'
} > "$file.partial"
mv "$file.partial" "$file"
echo "results.sh: wrote $file"
