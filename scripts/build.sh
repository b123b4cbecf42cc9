#!/usr/bin/env bash
# Configures and builds steadylight into build/ (Release). Used by demo.sh and test.sh.
#   bash scripts/build.sh [--target TARGET] [DIR [CMAKE OPTIONS...]]
#       (another folder and options: test.sh --sanitize; one target: demo.sh builds the program only)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
target=()
if [ "${1:-}" == --target ]; then
  target=(--target "$2")
  shift 2
fi
dir=${1:-build}
shift || true
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
[ -f "$dir/CMakeCache.txt" ] || cmake -S . -B "$dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build "$dir" "${target[@]}" --parallel "$(nproc)"
