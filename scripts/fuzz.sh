#!/usr/bin/env bash
# Builds the libFuzzer harnesses (fuzz/) with clang, AddressSanitizer and UndefinedBehaviorSanitizer
# into build-fuzz/ and runs each one for SECONDS (default 60), two at a time (one per core), on
# its seeds (the repository's own files) and the corpus kept in build-fuzz/fuzz/corpus-NAME from
# earlier runs. Limits: an input taking more than 1 s, or more than 2 GB at once or in all, is a
# finding, as is a crash or a sanitizer report; libFuzzer stops a target at its first finding and
# leaves the input in build-fuzz/fuzz/findings/. Prints executions, findings and peak memory per
# target and exits non-zero on any finding. Turn a finding into a test by copying its input to
# fuzz/regressions/NAME/ (the test fuzz.NAME replays it).
#   bash scripts/fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
bash scripts/setup.sh clang
dir=build-fuzz
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g -O1"
if [ ! -f $dir/CMakeCache.txt ]; then
  generator=()
  command -v ninja >/dev/null && generator=(-G Ninja)
  CC=clang CXX=clang++ cmake -S . -B $dir "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS=$flags" "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined" \
    -DSTEADYLIGHT_BUILD_FUZZERS=ON -DSTEADYLIGHT_BUILD_TESTS=OFF -DSTEADYLIGHT_BUILD_BENCHMARKS=OFF
fi
cmake --build $dir --parallel "$(nproc)"

work=$dir/fuzz
mkdir -p $work/findings
run_target() {  # name files_folder seeds(;-separated)
  local name=$1 files=$2 seeds=$3
  local seed_dir=$work/seeds-$name corpus=$work/corpus-$name
  rm -rf "$seed_dir"
  mkdir -p "$seed_dir" "$corpus"
  local s
  for s in ${seeds//;/ }; do
    if [ -d "$s" ]; then cp "$s"/* "$seed_dir"/; else cp "$s" "$seed_dir"/; fi
  done
  [ -d "fuzz/regressions/$name" ] && cp fuzz/regressions/"$name"/* "$seed_dir"/
  rm -f $work/findings/"$name"-*
  STEADYLIGHT_FUZZ_FILES=$files ASAN_OPTIONS=allocator_may_return_null=0 \
    $dir/fuzz/fuzz_"$name" -max_total_time="$seconds" -timeout=1 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix=$work/findings/"$name"- "$corpus" "$seed_dir" \
    > $work/"$name".log 2>&1 || true
}
selected=("$@")
lines=()
while IFS= read -r line; do
  name=${line%%|*}
  if [ ${#selected[@]} -eq 0 ] || [[ " ${selected[*]} " == *" $name "* ]]; then lines+=("$line"); fi
done < $dir/fuzz_targets.txt
running=0
for line in "${lines[@]}"; do
  IFS='|' read -r name files seeds <<< "$line"
  run_target "$name" "$files" "$seeds" &
  running=$((running + 1))
  if [ $running -ge "$(nproc)" ]; then wait -n; running=$((running - 1)); fi
done
wait

printf '%-16s %14s %8s %9s %13s %13s\n' target executions crashes timeouts "out of memory" "peak RSS (MB)"
total=0
findings=0
for line in "${lines[@]}"; do
  name=${line%%|*}
  log=$work/$name.log
  execs=$(grep -oP 'stat::number_of_executed_units:\s+\K[0-9]+' "$log" | tail -1 || true)
  rss=$(grep -oP 'stat::peak_rss_mb:\s+\K[0-9]+' "$log" | tail -1 || true)
  crashes=$(find $work/findings -name "$name-crash-*" -o -name "$name-leak-*" -o -name "$name-slow-unit-*" | wc -l)
  timeouts=$(find $work/findings -name "$name-timeout-*" | wc -l)
  ooms=$(find $work/findings -name "$name-oom-*" | wc -l)
  # A run that ended without its final statistics died some other way: a finding too.
  grep -q 'stat::number_of_executed_units' "$log" || crashes=$((crashes > 0 ? crashes : 1))
  printf '%-16s %14s %8s %9s %13s %13s\n' "$name" "${execs:-0}" "$crashes" "$timeouts" "$ooms" "${rss:-?}"
  total=$((total + ${execs:-0}))
  findings=$((findings + crashes + timeouts + ooms))
done
echo "executions in all: $total; findings: $findings (inputs in $work/findings, logs in $work/NAME.log)"
[ "$findings" -eq 0 ]
