#!/usr/bin/env bash
# Packs the Blender add-on (blender/steadylight_blender/) as a zip that Blender's
# Preferences > Add-ons > Install accepts, and prints the zip's path as its last line.
#   bash scripts/blender_addon.sh [OUT.zip]   (default: build/steadylight_blender.zip)
set -euo pipefail
cd "$(dirname "$0")/.."
out=$(realpath -m "${1:-build/steadylight_blender.zip}")
mkdir -p "$(dirname "$out")"
python3 - "$out" <<'PY'
import os, sys, zipfile
out = sys.argv[1]
with zipfile.ZipFile(out + ".part", "w", zipfile.ZIP_DEFLATED) as z:
    for name in sorted(os.listdir("blender/steadylight_blender")):
        if name.endswith(".py"):
            z.write(os.path.join("blender/steadylight_blender", name), "steadylight_blender/" + name)
os.replace(out + ".part", out)
PY
echo "$out"
