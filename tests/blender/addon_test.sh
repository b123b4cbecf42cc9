#!/usr/bin/env bash
# The Blender add-on in a real Blender 3.4, headless: installed from the zip that
# scripts/blender_addon.sh writes, it renders a small .blend (tests/blender/make_test_room.py: a
# room with a sun through a window, a world colour, an area lamp, a moving cube, frames 1-3)
# with `blender -b FILE --addons steadylight_blender -E STEADYLIGHT -a`, and
# - Blender writes the three frames, and every layer steadylight wrote is in them as a pass,
#   pixel for pixel (Blender's multilayer EXR output read back);
# - steadylight's EXRs from the add-on's run are byte for byte the command line's render of the
#   same export with the same options;
# - the passes the add-on registers are the layers of every method and choice of Passes
#   (check_passes.py), and with Passes set to Light Terms a frame holds the four terms only;
# - worlds (an HDRI, Blender's sky) and round lamps export as steadylight reads them
#   (export_variants.py);
# - a transparent film gives Combined an alpha of 0 where the world is seen;
# - Submit to Slurm writes the jobs of the same render (a dry run);
# - a break after the first frame leaves a folder the next render resumes: the static cache
#   loaded, frame 1 kept, frames 2 and 3 rendered;
# - a steadylight too old for the add-on stops the render with a message saying so.
set -euo pipefail
binary=$(realpath "$1") source=$(realpath "$2") out=$3
here=$source/tests/blender

rm -rf "$out"
mkdir -p "$out/bin"
out=$(realpath "$out")
ln -s "$binary" "$out/bin/steadylight"
export PATH=$out/bin:$PATH BLENDER_USER_SCRIPTS=$out/scripts
zip=$(bash "$source/scripts/blender_addon.sh" "$out/steadylight_blender.zip" | tail -1)
blender -b --factory-startup --python-exit-code 1 \
  --python-expr "import bpy; bpy.ops.preferences.addon_install(filepath='$zip')" > "$out/install.log" 2>&1
[ -f "$out/scripts/addons/steadylight_blender/__init__.py" ] || { cat "$out/install.log"; echo "the zip did not install"; exit 1; }

blender -b --factory-startup --python-exit-code 1 --python "$here/make_test_room.py" -- "$out/room.blend" > /dev/null
render() {  # render OUTPUT_PREFIX [blender argument...]: the animation through the add-on
  local prefix=$1
  shift
  blender -b "$out/room.blend" --factory-startup --addons steadylight_blender "$@" -E STEADYLIGHT \
    -o "$prefix####" -F OPEN_EXR_MULTILAYER -a
}
render "$out/frames/room_" > "$out/render.log" 2>&1 || { tail -30 "$out/render.log"; echo "the add-on's render failed"; exit 1; }
job=$(ls -d "$out"/room_steadylight/Scene_*)
here=$here python3 - "$out/frames" "$job" <<'PY'
import os, sys
sys.path.insert(0, os.environ["here"])
import exr_file
frames, job = sys.argv[1:]
for f in (1, 2, 3):
    blender, size = exr_file.read_exr(os.path.join(frames, f"room_{f:04d}.exr"))
    ours, _ = exr_file.read_exr(os.path.join(job, f"Scene_{f:04d}.exr"))
    assert size == (64, 48), size
    missing = sorted(set(ours) - set(blender))
    assert not missing, f"frame {f}: layers not in Blender's result: {missing}"
    for name, values in ours.items():
        assert blender[name] == values, f"frame {f}: {name} differs in Blender's output"
    combined = blender["ViewLayer.Combined.R"]
    assert sum(combined) / len(combined) > 0.05, "a dark frame"
    assert set(blender["ViewLayer.Combined.A"]) == {1.0}, "an opaque film has alpha 1"
    assert max(blender["ViewLayer.influence.X"]) > 0, "the influence pass is empty"
print(f"Blender's frames hold every layer of steadylight's, pixel for pixel ({len(ours)} channels)")
PY

# The command line on the same export, the same options, gives the same bytes.
options=$(sed -n 's/^\$ .* --frames [^ ]* //p' "$job/steadylight_blender.log" | head -1)
# shellcheck disable=SC2086 # the options as the add-on passed them, one word each
"$binary" render "$job/Scene.json" --out "$out/cli" --frames 1-3 $options --quiet
for f in 0001 0002 0003; do
  cmp "$job/Scene_$f.exr" "$out/cli/Scene_$f.exr" || { echo "frame $f: the add-on's EXR is not the command line's"; exit 1; }
done
echo "the add-on's EXRs are the command line's, byte for byte"

blender -b --factory-startup --addons steadylight_blender --python-exit-code 1 \
  --python "$here/check_passes.py" -- "$job/Scene.json" "$out/passes" 2>&1 | tee "$out/passes.log" | grep check_passes

blender -b "$out/room.blend" --factory-startup --addons steadylight_blender --python-exit-code 1 \
  --python "$here/export_variants.py" -- "$out/variants" 2>&1 | tee "$out/variants.log" | grep export_variants

# A break after frame 1 (another sample count: another folder), then the render again.
samples="import bpy; bpy.context.scene.steadylight.samples = 4"
if STEADYLIGHT_ADDON_TEST_BREAK_AFTER=1 render "$out/broken/room_" --python-expr "$samples" > "$out/break.log" 2>&1; then
  echo "a render broken after frame 1 ended as if it had finished"; exit 1
fi
broken=$(ls -d "$out"/room_steadylight/Scene_* | grep -v "$job")
[ -f "$broken/Scene_0001.manifest.json" ] && [ ! -f "$broken/Scene_0003.manifest.json" ] \
  || { echo "the break did not stop after frame 1"; ls "$broken"; exit 1; }
render "$out/resumed/room_" --python-expr "$samples" > "$out/resume.log" 2>&1 || { tail -20 "$out/resume.log"; exit 1; }
tail -4 "$broken/steadylight_blender.log"
grep -q "static cache: .*loaded" "$broken/steadylight_blender.log" || { echo "the resumed run computed the cache again"; exit 1; }
grep -q "2 frame(s) written, 1 complete ones skipped" "$broken/steadylight_blender.log" \
  || { echo "the resumed run did not keep frame 1 and render frames 2 and 3"; exit 1; }
ls "$out"/resumed/room_000{1,2,3}.exr > /dev/null

# Submit to Slurm, as a dry run (tests/farm/ runs real Slurm clusters): the job scripts of a bake,
# one chunk and the finishing job, rendering with the add-on's options into the folder a render
# from Blender would use.
blender -b "$out/room.blend" --factory-startup --addons steadylight_blender --python-exit-code 1 \
  --python-expr "import bpy; bpy.context.scene.steadylight.samples = 2; bpy.ops.steadylight.submit(dry_run=True)" \
  > "$out/submit.log" 2>&1 || { tail -20 "$out/submit.log"; echo "Submit to Slurm failed"; exit 1; }
grep -q "would run: sbatch --parsable .*/slurm/bake_0.sh" "$out/submit.log" \
  && grep -q "would run: sbatch .*--array=0-0 .*/slurm/render_0.sh" "$out/submit.log" \
  || { cat "$out/submit.log"; echo "Submit to Slurm did not show the bake and render jobs"; exit 1; }
grep -q -- "--blender-view-layer ViewLayer .*--spp 2" "$(ls -d "$out"/room_steadylight/Scene_*/slurm/render_0.sh | head -1)" \
  || { echo "the farm's chunks do not render with the add-on's options"; exit 1; }

# Film > Transparent: Combined's alpha is 0 where the camera sees the world through the window.
blender -b "$out/room.blend" --factory-startup --addons steadylight_blender \
  --python-expr "import bpy; bpy.context.scene.render.film_transparent = True" -E STEADYLIGHT \
  -o "$out/transparent/room_####" -F OPEN_EXR_MULTILAYER -f 2 > "$out/transparent.log" 2>&1
here=$here python3 - "$out/transparent/room_0002.exr" <<'PY'
import os, sys
sys.path.insert(0, os.environ["here"])
import exr_file
alpha = exr_file.read_exr(sys.argv[1])[0]["ViewLayer.Combined.A"]
see_world = sum(a == 0 for a in alpha)
assert 50 < see_world < len(alpha) / 2 and max(alpha) == 1, f"{see_world} pixels of alpha 0, max {max(alpha)}"
print(f"a transparent film: alpha 0 at the {see_world} pixels that see the sky")
PY

# Passes > Light Terms: steadylight renders with --layers terms, and Blender's frame holds
# Combined and the four terms of the light, no analysis pass.
blender -b "$out/room.blend" --factory-startup --addons steadylight_blender \
  --python-expr "import bpy; bpy.context.scene.steadylight.layers = 'terms'" -E STEADYLIGHT \
  -o "$out/terms/room_####" -F OPEN_EXR_MULTILAYER -f 2 > "$out/terms.log" 2>&1
grep -q -- "--layers terms " "$out"/room_steadylight/Scene_*/steadylight_blender.log \
  || { tail -20 "$out/terms.log"; echo "Light Terms did not render with --layers terms"; exit 1; }
here=$here python3 - "$out/terms/room_0002.exr" <<'PY'
import os, sys
sys.path.insert(0, os.environ["here"])
import exr_file
channels = exr_file.read_exr(sys.argv[1])[0]
passes = sorted({name.split(".")[1] for name in channels})
assert passes == ["Combined", "caustic", "direct", "indirect", "specular"], passes
assert max(channels["ViewLayer.direct.R"]) > 0, "the direct pass is empty"
print(f"Passes > Light Terms: the frame holds {', '.join(passes)}")
PY

# A steadylight older than the add-on needs.
mkdir -p "$out/old"
printf '#!/bin/sh\necho "steadylight 0.1.0"\n' > "$out/old/steadylight"
chmod +x "$out/old/steadylight"
if PATH=$out/old:$PATH render "$out/old/room_" > "$out/old.log" 2>&1; then
  echo "an old steadylight rendered"; exit 1
fi
grep -q "is steadylight 0.1.0; this add-on needs 0.2.0 or later" "$out/old.log" \
  || { tail -5 "$out/old.log"; echo "no message about the old version"; exit 1; }
echo "addon_test: passed"
