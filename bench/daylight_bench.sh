#!/usr/bin/env bash
# Daylight against an area light: BALL (lit by its ceiling panel) and scenes/daylit_room.json (the
# same room closed, lit by a sun and a sky through a window marked as a portal), each rendered by
# the command line with the photon and the localized method, one after the other, from empty
# folders (static pass included), at the same size and photon count. Prints per run the whole
# run's wall time, the mean frame time from the frames' statistics and the mean
# distant_photons_inside; then, per scene, the photon / localized ratio, and the daylit room's
# localized frame over BALL's. The goals: that frame within 1.5x of BALL's, its ratio at least
# BALL's. Last, what the localized frames did on average (from their statistics): photon paths
# traced again, dynamic photons stored, L_y records, and each phase's seconds, which say where a
# frame's time goes and how much of the light the moving object changes; and the daylit frame
# without its L_y phase, against BALL's whole frame: what making L_y free alone would reach.
# Prints, asserts nothing.
#   bash bench/daylight_bench.sh [--frames A-B] [--size WxH] [--photons N]   (default: 0-29, 320x240, 200000)
set -euo pipefail
cd "$(dirname "$0")/.."
frames=0-29 size=320x240 photons=200000
while [ $# -gt 0 ]; do
  case "$1" in
    --frames) frames=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --photons) photons=$2; shift 2 ;;
    *) echo "daylight_bench: unknown argument $1" >&2; exit 2 ;;
  esac
done
[ -x build/steadylight ] || bash scripts/build.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "frames $frames, $size, $photons photons; machine load $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-12s %-9s %10s %12s %16s\n' scene method wall 'frame mean' 'distant inside'
for scene in ball daylit_room; do
  for method in photon localized; do
    out=$work/${scene}_$method
    start=$(date +%s%N)
    build/steadylight render "scenes/$scene.json" --frames "$frames" --size "$size" --photons "$photons" \
      --method "$method" --out "$out" --quiet
    wall_ms=$(( ($(date +%s%N) - start) / 1000000 ))
    python3 - "$scene" "$method" "$wall_ms" "$out" <<'PY' | tee -a "$work/table"
import glob, json, sys
scene, method, wall_ms, folder = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
stats = [json.load(open(f)) for f in sorted(glob.glob(folder + "/*.stats.json"))]
frame = sum(s["seconds"]["total"] for s in stats) / len(stats)
inside = [s["distant_photons_inside"] for s in stats if "distant_photons_inside" in s]
share = f"{100 * sum(inside) / len(inside):.1f}%" if inside else "-"
print(f"{scene:<12} {method:<9} {wall_ms / 1000:8.1f} s {frame:10.3f} s {share:>16}")
PY
  done
done
python3 - "$work/table" <<'PY'
import sys
rows = {}
for line in open(sys.argv[1]):
    f = line.split()
    rows[(f[0], f[1])] = (float(f[2]), float(f[4]))
for scene in ("ball", "daylit_room"):
    print(f"{scene}: photon / localized, whole run {rows[(scene, 'photon')][0] / rows[(scene, 'localized')][0]:.2f}x, "
          f"per frame {rows[(scene, 'photon')][1] / rows[(scene, 'localized')][1]:.2f}x")
print(f"daylit_room / ball, localized frame: {rows[('daylit_room', 'localized')][1] / rows[('ball', 'localized')][1]:.2f}x; "
      f"whole run {rows[('daylit_room', 'localized')][0] / rows[('ball', 'localized')][0]:.2f}x")
PY
echo "localized frames, mean per frame:"
python3 - "$work" <<'PY'
import glob, json, sys
work = sys.argv[1]
print(f"{'scene':<12} {'retraced':>9} {'dynamic':>9} {'records':>8} {'photons':>8} {'influence':>9} {'L_y':>8} {'L_t':>8} "
      f"{'shading':>8} {'other':>8}")
frame = {}
for scene in ("ball", "daylit_room"):
    stats = [json.load(open(f)) for f in sorted(glob.glob(f"{work}/{scene}_localized/*.stats.json"))]
    mean = lambda get: sum(get(s) for s in stats) / len(stats)
    phases = {k: mean(lambda s, k=k: s["seconds"][k]) for k in ("photon_tracing", "influence", "cache", "correction", "shading")}
    total = mean(lambda s: s["seconds"]["total"])
    frame[scene] = (total, total - phases["cache"])
    print(f"{scene:<12} {mean(lambda s: s['photons']['retraced_paths']):9.0f} {mean(lambda s: s['photons']['dynamic_stored']):9.0f} "
          f"{mean(lambda s: s['irradiance_records']):8.0f} " + " ".join(f"{t:8.3f}s" for t in phases.values())
          + f" {total - sum(phases.values()):8.3f}s")
photon = {}
for line in open(f"{work}/table"):
    f = line.split()
    if f[1] == "photon":
        photon[f[0]] = float(f[4])
# Every phase but L_y scales with how much of the light the moving object changes; the frame
# without L_y (as if it cost nothing) bounds what shrinking L_y alone can reach.
without = frame["daylit_room"][1]
print(f"daylit_room localized frame without L_y: {without:.3f} s = {without / frame['ball'][0]:.2f}x BALL's frame; "
      f"photon / that {photon['daylit_room'] / without:.2f}x")
PY
