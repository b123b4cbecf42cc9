#!/usr/bin/env bash
# Reuse side by side (docs/localized.md, "Photon paths reused" and "Pixels reused"): each scene
# rendered by the command line with the localized method, with reuse (the default) and with
# --no-reuse, one after the other on the same machine, each run from an empty folder (its
# static pass included, as a user's first run). Prints per run the whole run's wall time, the
# static frame's and paths' set-up from the log, the mean per frame of every phase, of the
# pixels reused / looked up again / redone without their shadow rays / redone whole, of the pixels per changed
# term and of the photon paths traced; and whether the two runs' PNGs are byte for byte the
# same (then the truth suite's error and temporal noise are the same too). Prints, asserts
# nothing.
#   bash bench/reuse_bench.sh [--frames N] [--size WxH] [SCENE...]     (default: ball table, all frames, 320x240)
set -euo pipefail
cd "$(dirname "$0")/.."
frames="" size=320x240
while [ $# -gt 0 ]; do
  case "$1" in
    --frames) frames=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    *) break ;;
  esac
done
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(ball table)
binary=build/steadylight
[ -x "$binary" ] || bash scripts/build.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

summarize() {  # FOLDER LOG WALL
  python3 - "$@" <<'PY'
import glob, json, re, sys
folder, log, wall = sys.argv[1], sys.argv[2], float(sys.argv[3])
stats = [json.load(open(f)) for f in sorted(glob.glob(folder + "/*.stats.json"))]
n = len(stats)
mean = lambda get: sum(get(s) for s in stats) / n
secs = lambda k: mean(lambda s: s["seconds"][k])
pix = lambda k: mean(lambda s: s.get("pixels", {}).get(k, 0))
setup = "; ".join(re.sub(r"^.*\] ", "", l.strip()) for l in open(log) if "static photon paths:" in l or "static frame:" in l or "static cache:" in l)
print(f"  wall {wall:.1f} s for {n} frames ({wall / n:.3f} s a frame)")
print(f"  set-up: {setup}")
print(f"  per frame: total {secs('total'):.3f} s = photons {secs('photon_tracing'):.3f} + L_y {secs('cache'):.3f} + influence {secs('influence'):.3f}"
      f" + L_t {secs('correction'):.3f} + shading {secs('shading'):.3f} (caustics {secs('caustics'):.3f} cpu)")
total = pix("reused") + pix("looked_up_again") + pix("direct_again") + pix("redone_but_direct") + pix("redone")
if total:
    print(f"  pixels a frame: reused {pix('reused'):.0f}, looked up again {pix('looked_up_again'):.0f},"
          f" direct again {pix('direct_again'):.0f}, redone but direct {pix('redone_but_direct'):.0f}, redone {pix('redone'):.0f};"
          f" changed camera {pix('changed_camera'):.0f}, direct {pix('changed_direct'):.0f}, indirect {pix('changed_indirect'):.0f},"
          f" caustic {pix('changed_caustic'):.0f}")
print(f"  photon paths traced a frame: {mean(lambda s: s['photons']['retraced_paths']):.0f}")
PY
}

for scene in "${scenes[@]}"; do
  echo "== $scene $size${frames:+, frames $frames} (localized; machine load $(cut -d' ' -f1-3 /proc/loadavg))"
  walls=()
  for mode in reuse no-reuse; do
    extra=(); [ $mode = no-reuse ] && extra=(--no-reuse)
    [ -n "$frames" ] && extra+=(--frames "$frames")
    start=$(date +%s.%N)
    rm -f "$work/$mode.log"
    "$binary" render "scenes/$scene.json" --size "$size" --out "$work/$mode" --quiet --log "$work/$mode.log" "${extra[@]}"
    wall=$(python3 -c "import sys; print(float(sys.argv[2]) - float(sys.argv[1]))" "$start" "$(date +%s.%N)")
    walls+=("$wall")
    echo "$mode:"
    summarize "$work/$mode" "$work/$mode.log" "$wall"
  done
  same=yes
  for png in "$work"/reuse/*.png; do cmp -s "$png" "$work/no-reuse/$(basename "$png")" || same=no; done
  python3 -c "import sys; print(f'  no-reuse / reuse, whole run: {float(sys.argv[2]) / float(sys.argv[1]):.2f}x; PNGs identical: {sys.argv[3]}')" \
    "${walls[0]}" "${walls[1]}" "$same"
  rm -rf "$work/reuse" "$work/no-reuse"
done
