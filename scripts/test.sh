#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite through CTest.
#   bash scripts/test.sh                              build/, Release
#   bash scripts/test.sh --sanitize address,undefined  build-address-undefined/, with those sanitizers
#   (any list clang or gcc's -fsanitize= takes; the thread sanitizer's suppressions for TBB and
#   Embree, which are not instrumented, are not written yet)
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" != --sanitize ]; then
  bash scripts/build.sh
  ctest --test-dir build --output-on-failure --timeout 900
  exit
fi
sanitizers=${2:?--sanitize needs a list: address,undefined or thread}
dir=build-${sanitizers//,/-}
flags="-fsanitize=$sanitizers -fno-omit-frame-pointer -fno-sanitize-recover=all"
bash scripts/build.sh "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS=$flags" \
  "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=$sanitizers"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Sanitized code runs several times slower: a longer timeout.
ctest --test-dir "$dir" --output-on-failure --timeout 3600
