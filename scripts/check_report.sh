#!/usr/bin/env bash
# Opens a `steadylight report` page in headless Chromium (Debian's `chromium`), with every
# host name unresolvable so that nothing can come from the network, and checks that it rendered:
# every image decoded, the SVG plots are in the DOM with points, the page holds each --expect
# text (a plot's legend, a table's column), and a screenshot is not blank.
#   scripts/check_report.sh [--expect TEXT]... REPORT.html [SCREENSHOT.png]   (default: REPORT.png)
# Exit status: 0 when it rendered, 1 when a check failed; without chromium 77 (CTest reports the
# test as skipped), or 1 under CI=true, where a check that cannot run fails.
set -euo pipefail
expected=()
while [ "${1:-}" == --expect ]; do
  expected+=("$2")
  shift 2
done
report=${1:?usage: check_report.sh [--expect TEXT]... REPORT.html [SCREENSHOT.png]}
screenshot=${2:-${report%.html}.png}

browser=$(command -v chromium || command -v chromium-browser || true)
source "$(dirname "$0")/../tests/support/skip.sh"
[ -n "$browser" ] || skip_without_tool "chromium is not on PATH (Debian: apt-get install chromium)"
[ -s "$report" ] || { echo "FAIL: no report at $report"; exit 1; }
url="file://$(realpath "$report")"
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
flags=(--headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir="$profile"
       --host-resolver-rules="MAP * ~NOTFOUND" --virtual-time-budget=10000)
fail() { echo "FAIL: $*"; [ -s "$profile/chromium.log" ] && tail -n 20 "$profile/chromium.log"; exit 1; }

# The DOM after the load event: the page's own script has counted the decoded images by then.
dom=$("$browser" "${flags[@]}" --dump-dom "$url" 2>"$profile/chromium.log") || fail "chromium --dump-dom failed"
decoded=$(grep -o 'data-images-decoded="[0-9]*/[0-9]*"' <<<"$dom" | grep -o '[0-9]*/[0-9]*' || true)
[ -n "$decoded" ] || fail "the page did not report its images (did it load?)"
[ "${decoded%/*}" = "${decoded#*/}" ] && [ "${decoded%/*}" -gt 0 ] || fail "images decoded: $decoded"
plots=$(grep -o '<svg' <<<"$dom" | wc -l)
lines=$(grep -oE '<polyline[^>]* points="[0-9.]+,[0-9.]+[^"]*"' <<<"$dom" | wc -l)
frames=$(grep -o '<figure class="frame"' <<<"$dom" | wc -l)
tables=$(grep -o '<table' <<<"$dom" | wc -l)
[ "$plots" -ge 2 ] && [ "$lines" -ge 2 ] || fail "plots in the DOM: $plots, lines with points: $lines"
[ "$frames" -ge 1 ] && [ "$tables" -ge 1 ] || fail "frames: $frames, tables: $tables"
for text in "${expected[@]}"; do
  grep -qF -- "$text" <<<"$dom" || fail "the page lacks: $text"
done

# A screenshot of the top of the page must show more than a blank page: count distinct rows of
# pixels (a blank page has one or two).
"$browser" "${flags[@]}" --window-size=1280,1600 --screenshot="$(realpath -m "$screenshot")" "$url" \
  2>>"$profile/chromium.log" >/dev/null || fail "chromium --screenshot failed"
[ -s "$screenshot" ] || fail "no screenshot written"
rows=$(python3 - "$screenshot" <<'PY'
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
pos, idat, width, channels = 8, b"", 0, 3
while pos < len(data):
    length, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + length]
    if kind == b"IHDR":
        width, color_type = struct.unpack(">I", body[:4])[0], body[9]
        channels = {0: 1, 2: 3, 4: 2, 6: 4}[color_type]
    elif kind == b"IDAT":
        idat += body
    pos += 12 + length
raw, stride = zlib.decompress(idat), 1 + width * channels
print(len({raw[i:i + stride] for i in range(0, len(raw), stride)}))
PY
)
[ "$rows" -gt 50 ] || fail "the screenshot looks blank ($rows distinct pixel rows)"
echo "ok: $decoded images decoded, $plots plots, $lines lines, $frames frames, $tables tables; screenshot $screenshot ($rows distinct rows)"
