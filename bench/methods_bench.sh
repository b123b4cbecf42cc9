#!/usr/bin/env bash
# The README's headline: each scene rendered by the command line with the localized method, the
# photon method, and the localized method again, each from an empty folder (the static pass and
# the writing included, as a user's first run): the whole runs' wall times, and the ratio of the
# photon run to the mean of the localized runs around it. The short localized run is timed on
# both sides of the long photon run, since on a shared machine its time wanders by a tenth or
# more from minute to minute, and one run would pair it with a single minute. Error against
# converged references is quality_bench's. Prints, asserts nothing.
#   bash bench/methods_bench.sh [SCENE:FRAMES:SIZE[:LAYERS]...]
#       default: ball:0-59:320x240 table:0-29:320x240 ball:0-19:1280x960 ball:0-19:1280x960:terms;
#       LAYERS is --layers for both methods (all when left out).
set -euo pipefail
cd "$(dirname "$0")/.."
runs=("$@")
[ ${#runs[@]} -gt 0 ] || runs=(ball:0-59:320x240 table:0-29:320x240 ball:0-19:1280x960 ball:0-19:1280x960:terms)
[ -x build/steadylight ] || bash scripts/build.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Wall time in milliseconds of one render into an empty folder.
render_s() {  # SCENE FRAMES SIZE LAYERS METHOD
  local out=$work/$1_$5
  rm -rf "$out"
  local start
  start=$(date +%s%N)
  build/steadylight render "scenes/$1.json" --frames "$2" --size "$3" --layers "$4" --method "$5" --out "$out" \
    --quiet
  echo $(( ($(date +%s%N) - start) / 1000000 ))
}

printf '%-7s %-7s %-10s %-7s %12s %22s %10s\n' scene frames size layers photon 'localized (before, after)' ratio
# Milliseconds as seconds, and the ratio of the first to the mean of the other two.
seconds() { python3 -c "print(f'{$1 / 1000:.1f}')"; }
ratio() { python3 -c "print(f'{$1 / (($2 + $3) / 2):.2f}')"; }
for run in "${runs[@]}"; do
  IFS=: read -r scene frames size layers <<< "$run"
  layers=${layers:-all}
  before=$(render_s "$scene" "$frames" "$size" "$layers" localized)
  photon=$(render_s "$scene" "$frames" "$size" "$layers" photon)
  after=$(render_s "$scene" "$frames" "$size" "$layers" localized)
  printf '%-7s %-7s %-10s %-7s %10s s %11s s, %6s s %9sx\n' "$scene" "$frames" "$size" "$layers" \
    "$(seconds "$photon")" "$(seconds "$before")" "$(seconds "$after")" "$(ratio "$photon" "$before" "$after")"
done
