#!/usr/bin/env bash
# Sets up, builds and renders the demo animation BALL into out/ball/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
./build/steadylight render scenes/ball.json --out out/ball "$@"
