#!/usr/bin/env bash
# Configures and builds steadylight into build/ (Release). Used by demo.sh and test.sh.
#   bash scripts/build.sh [DIR [CMAKE OPTIONS...]]   (another folder and options: test.sh --sanitize)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
dir=${1:-build}
shift || true
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
[ -f "$dir/CMakeCache.txt" ] || cmake -S . -B "$dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build "$dir" --parallel "$(nproc)"
