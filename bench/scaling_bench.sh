#!/usr/bin/env bash
# How a frame's cost grows with the image and with the photons, for the localized and the photon
# method: a scene rendered by the command line at each size (default photons) and with each
# photon count (at the first size), each run from an empty folder. Per run: the mean time of a
# frame (the frames' own `total` seconds from their stats), what the rest of the run took (the
# static pass, the static frame, start-up and the last frame's writing: the wall time less the
# frames), and the peak resident memory (`/usr/bin/time`). Prints, asserts nothing.
#   bash bench/scaling_bench.sh [--scene NAME] [--frames LIST] [--sizes WxH,...] [--photons N,...]
#       default: ball, frames 0-4, sizes 320x240,640x480,1280x960,1920x1080, photons 200000,800000,3200000
set -euo pipefail
cd "$(dirname "$0")/.."
scene=ball frames=0-4
sizes=320x240,640x480,1280x960,1920x1080
photon_counts=200000,800000,3200000
while [ $# -gt 0 ]; do
  case "$1" in
    --scene) scene=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --sizes) sizes=$2; shift 2 ;;
    --photons) photon_counts=$2; shift 2 ;;
    *) echo "scaling_bench: unknown option $1" >&2; exit 1 ;;
  esac
done
[ -x build/steadylight ] || bash scripts/build.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# One run: prints its row.
run() {  # METHOD SIZE PHOTONS
  local out=$work/run
  rm -rf "$out"
  local start
  start=$(date +%s.%N)
  /usr/bin/time -f %M -o "$work/rss" build/steadylight render "scenes/$scene.json" --frames "$frames" --size "$2" \
    --photons "$3" --method "$1" --out "$out" --quiet
  python3 - "$out" "$start" "$(date +%s.%N)" "$(cat "$work/rss")" "$1" "$2" "$3" <<'PY'
import glob, json, sys
out, start, end, rss_kb, method, size, photons = sys.argv[1:]
totals = [json.load(open(f))["seconds"]["total"] for f in sorted(glob.glob(out + "/*.stats.json"))]
wall = float(end) - float(start)
w, h = (int(v) for v in size.split("x"))
print(f"{method:<10} {size:>10} {int(photons):>9} {sum(totals) / len(totals):10.3f} s {wall - sum(totals):9.1f} s"
      f" {int(rss_kb) / 1024:8.0f} MB {int(rss_kb) * 1024 / (w * h):8.0f}")
PY
}

echo "$scene, frames $frames (machine load $(cut -d' ' -f1-3 /proc/loadavg))"
printf '%-10s %10s %9s %12s %11s %11s %8s\n' method size photons "a frame" "the rest" "peak" "B/pixel"
IFS=, read -r -a size_list <<< "$sizes"
IFS=, read -r -a photon_list <<< "$photon_counts"
for method in localized photon; do
  for size in "${size_list[@]}"; do run "$method" "$size" "${photon_list[0]}"; done
  for photons in "${photon_list[@]:1}"; do run "$method" "${size_list[0]}" "$photons"; done
done
