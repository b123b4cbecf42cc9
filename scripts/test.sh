#!/usr/bin/env bash
# Sets up, builds and runs the test suite through CTest.
#   bash scripts/test.sh
#       The README's test command, and CI's (.ci/run): the whole suite in build/ (Release), then
#       the AddressSanitizer and UndefinedBehaviorSanitizer build (build-address-undefined/) on
#       every test but the slowest and the repository checks (left_out_under_sanitizers below),
#       so that the run stays near 20 minutes on 2 cores.
#   bash scripts/test.sh --sanitize LIST [CTEST OPTION...]
#       The whole suite (or what the ctest options select, e.g. -R 'cli\.kill_resume') in
#       build-LIST/ with those sanitizers: address,undefined or thread. The
#       thread build links oneTBB built with ThreadSanitizer (scripts/build_instrumented_tbb.sh)
#       and reads tests/sanitizers/thread_suppressions.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
# What the tests need beyond the build: clang-format (repo.format), Chromium (cli.report_chromium),
# sshfs and an SSH server (farm.sshfs), Blender (blender.addon; not the demo's: it renders alone)
# and NumPy, which Blender's own glTF exporter imports but Debian's blender package does not
# depend on.
bash scripts/setup.sh clang-format chromium sshfs openssh-server blender python3-numpy

# Left out of the sanitized pass: the tests over 10 s each under the address and undefined
# sanitizers (60% of that suite's time): the kill-and-resume and farm runs, the truth suite's
# renders, the longest animation tests.
left_out_under_sanitizers='^(cli\.(kill_resume|blender_room|disk_faults|farm_share|resume)|farm\.(slurm|slurm_faults|sshfs)|Scenes/TruthSuite\.'
left_out_under_sanitizers+='|Localized\.(CacheFileOfTheLightOff|FrozenCacheRecomputes|SwitchedOnLight|StaticCacheIsSaved)'
left_out_under_sanitizers+='|DynamicPhotons\.StaticPathsRetracedWhere|ComposedMaps\.MovingAbsorbingGlass'
left_out_under_sanitizers+='|PixelReuse\.PixelsWithNoTermChanged'
# The Blender add-on's test runs in the Release pass only: Blender's start-ups are most of it, and
# the steadylight code it runs is the sanitized suite's already.
left_out_under_sanitizers+='|blender\.'
# The repository's checks (format, documentation links, layers) read no build: the Release pass
# runs them.
left_out_under_sanitizers+='|repo\.)'

# Builds and runs the suite with the sanitizers of $1; further arguments go to ctest.
sanitized_suite() {
  local sanitizers=$1
  shift
  local dir=build-${sanitizers//,/-}
  local flags="-fsanitize=$sanitizers -fno-omit-frame-pointer -fno-sanitize-recover=all"
  # -O1 and line tables only: half the build time of -O2 -g, and stack traces keep file and line.
  local options=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS=$flags"
                 "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
                 "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=$sanitizers" -DSTEADYLIGHT_BUILD_BENCHMARKS=OFF)
  if [[ $sanitizers == *thread* ]]; then
    local tbb
    tbb=$(bash scripts/build_instrumented_tbb.sh "$dir")
    options+=("-DTBB_DIR=$tbb/lib/cmake/TBB")
    export LD_LIBRARY_PATH=$tbb/lib  # Embree's libtbb.so.12 is the instrumented one too
    export TSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/thread_suppressions.txt halt_on_error=1 second_deadlock_stack=1"
  fi
  bash scripts/build.sh "$dir" "${options[@]}"
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  # Sanitized code runs several times slower: a longer timeout.
  ctest --test-dir "$dir" --output-on-failure --timeout 3600 "$@"
}

if [ "${1:-}" == --sanitize ]; then
  sanitizers=${2:?--sanitize needs a list: address,undefined or thread}
  shift 2
  sanitized_suite "$sanitizers" --parallel "$(nproc)" "$@"
  exit
fi
bash scripts/build.sh
ctest --test-dir build --output-on-failure --timeout 900
sanitized_suite address,undefined --parallel "$(nproc)" --exclude-regex "$left_out_under_sanitizers"
