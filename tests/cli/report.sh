#!/usr/bin/env bash
# Renders three tiny BALL frames with the localized method, writes `steadylight report` for
# them and checks the page: every frame in the contact sheet, plots with a point per frame, the
# summary table, the AOV layers, nothing fetched from the network; then --frame, --out, a
# report on path-traced frames, a folder of several methods, a folder the release before wrote,
# and bad input. The pages it leaves (OUT/report.html, OUT/mixed/, OUT/older/) are what
# cli.report_chromium opens (report_chromium.sh).
set -euo pipefail
binary=$1 source=$2 out=$3

fail() { echo "FAIL: $*"; exit 1; }
has() { grep -qF -- "$1" "$2" || fail "$2 lacks: $1"; }

rm -rf "$out"
"$binary" render "$source/scenes/ball.json" --frames 0-2 --spp 1 --size 40x30 --photons 2000 --caustic-photons 0 \
  --gather-samples 32 --no-progress --out "$out"
"$binary" report "$out"
html=$out/report.html
[ -s "$html" ] || fail "no $html"
[ ! -e "$html.partial" ] || fail "$html.partial left behind"
for frame in 0 1 2; do has "<figure class=\"frame\" data-frame=\"$frame\">" "$html"; done
has "<th>localized</th>" "$html"
# The beauty once (the EXR holds it unnamed and as `beauty`), then all 10 AOVs, grey ones too.
for layer in beauty direct indirect caustic specular indirect_static L_y L_t influence static_records dynamic_records; do
  [ "$(grep -oF "<figure class=\"aov\" data-layer=\"$layer\">" "$html" | wc -l)" = 1 ] || fail "layer $layer not shown once"
done
! grep -qF 'aov-skipped' "$html" || fail "a layer was not shown"
has "ball, frame 1</h3>" "$html"
[ "$(grep -o '<svg' "$html" | wc -l)" -ge 3 ] || fail "fewer than 3 plots"
# Every polyline has one point per frame.
points=$(grep -o 'points="[^"]*"' "$html" | awk -F, '{ print NF - 1 }' | sort -u)
[ "$points" = 3 ] || fail "polylines with other than 3 points: $points"
! grep -qE 'src="https?:|<link|@import|url\(' "$html" || fail "the page fetches something"

"$binary" report "$out" --frame 2 --out "$out/frame2.html"
has "ball, frame 2</h3>" "$out/frame2.html"

# Path-traced frames have statistics too: the time per frame is plotted, a point per frame.
"$binary" render "$source/scenes/ball.json" --method path --frames 0-1 --spp 1 --size 16x12 --no-progress --out "$out/path"
"$binary" report "$out/path"
path_html=$out/path/report.html
has '<th>path</th>' "$path_html"
has '<th>camera samples (path)</th><td>192.0</td>' "$path_html"
! grep -qF 'No frame statistics' "$path_html" || fail "no statistics for the path frames"
grep -o '<polyline[^>]*data-series="path"[^>]*points="[^"]*"' "$path_html" | head -1 | grep -qE 'points="[^ ]+ [^ ]+"' \
  || fail "no time plot with two points for the path frames"

# One folder with several methods: frames 0-1 localized, 2-3 photon, 4-5 path-traced. The tables
# compare each method with the photon method, the plots have a line per method.
mixed=$out/mixed
small=(--spp 1 --size 40x30 --photons 2000 --caustic-photons 0 --gather-samples 32 --no-progress --out "$mixed")
"$binary" render "$source/scenes/ball.json" --frames 0-1 "${small[@]}"
"$binary" render "$source/scenes/ball.json" --frames 2-3 --method photon --overwrite "${small[@]}"
"$binary" render "$source/scenes/ball.json" --frames 4-5 --method path --overwrite "${small[@]}"
"$binary" report "$mixed"
for column in '<th>photon / localized</th>' '<th>photon / path</th>'; do has "$column" "$mixed/report.html"; done
for series in localized photon path; do has "data-series=\"$series\"" "$mixed/report.html"; done

# A folder as the release before wrote it: the shading time under seconds.direct.
older=$out/older
mkdir -p "$older" && cp "$out"/ball_000[0-2].* "$older/"
for stats in "$older"/*.stats.json; do
  python3 - "$stats" <<'PY'
import json, sys
stats = json.load(open(sys.argv[1]))
stats["seconds"]["direct"] = stats["seconds"].pop("shading")
json.dump(stats, open(sys.argv[1], "w"))
PY
done
"$binary" report "$older"
has "<th>localized</th>" "$older/report.html"
grep -qF '"shading":' "$older/ball_0000.stats.json" && fail "the older folder still has seconds.shading"

# Bad input: a clear message naming what is wrong, exit status 1.
expect_error() {  # expect_error REGEX ARGS...
  local regex=$1; shift
  set +e; message=$("$binary" report "$@" 2>&1); status=$?; set -e
  [ $status -eq 1 ] || fail "report $* exited with $status: $message"
  grep -Eq -- "$regex" <<<"$message" || fail "report $*: message does not match /$regex/: $message"
}
expect_error "error: .*nowhere: no such folder" "$out/nowhere"
expect_error "error: --frame: no EXR of frame 9" "$out" --frame 9
mkdir -p "$out/broken" && cp "$out"/ball_0000.* "$out/broken/" && echo '{"method": 3}' > "$out/broken/ball_0000.stats.json"
expect_error "error: .*broken/ball_0000.stats.json: not a frame statistics file" "$out/broken"
echo "ok"
