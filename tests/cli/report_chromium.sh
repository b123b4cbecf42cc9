#!/usr/bin/env bash
# The report pages cli.report (report.sh) left, opened in headless Chromium
# (scripts/check_report.sh): the demo-like page, the page of a folder holding several methods
# and a path-traced range (a legend entry per method, the ratio columns), and the page of a
# folder written with the release before's statistics keys.
#   tests/cli/report_chromium.sh SOURCE OUT
set -euo pipefail
source=$1 out=$2
check=$source/scripts/check_report.sh
bash "$check" "$out/report.html" "$out/screenshot.png"
bash "$check" --expect '>localized</text>' --expect '>photon</text>' --expect '>path</text>' \
  --expect 'photon / localized' --expect 'photon / path' "$out/mixed/report.html"
bash "$check" --expect 'localized' "$out/older/report.html"
