"""Run inside Blender on the test room (make_test_room.py) with the add-on enabled: what the export
writes for the worlds and lamps the room itself does not have, and that steadylight reads it.

    blender -b ROOM.blend --factory-startup --addons steadylight_blender --python export_variants.py -- OUT

- an Environment Texture (one of Blender's own HDRIs) through a Mapping node turned by 30
  degrees: the image copied beside the scene, the rotation and strength carried; packed into
  the .blend, written out beside the scene;
- disc and ellipse lamps: emitting polygons whose radiance times area is the lamp's power / 4
  (Cycles' radiance P / (4 A), over the polygon);
- a Nishita Sky Texture: Blender's parameters in degrees;
- a node the export does not carry (a Noise Texture into the Background): a warning, not silence;
- lamps that move: a point lamp (moved by the .glb's node animation) and the square area lamp
  (its own tracks), both listed as moving; frame 3 of that export renders as the export of the
  room with the lamps standing where they are at frame 3.
Each export is read by `steadylight info`.
"""
import json
import math
import os
import subprocess
import sys

import bpy

from steadylight_blender import scene_export
from steadylight_blender.program import checked_program

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exr_file  # noqa: E402 (beside this file)
import make_test_room  # noqa: E402

out = sys.argv[sys.argv.index("--") + 1]
program = checked_program("")
scene = bpy.context.scene
world = scene.world.node_tree
background = world.nodes["Background"]
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


def export(name):
    folder = os.path.join(out, name)
    result = scene_export.export_scene(scene, folder, name)
    with open(os.path.join(folder, name + ".json")) as f:
        wrapper = json.load(f)
    info = subprocess.run([program, "info", os.path.join(folder, name + ".json")], capture_output=True, text=True)
    check(info.returncode == 0, f"{name}: steadylight info failed: {info.stderr}")
    return wrapper, result.warnings, info.stdout, folder


# An HDRI through a turned Mapping node, and round lamps.
texture = world.nodes.new("ShaderNodeTexEnvironment")
texture.image = bpy.data.images.load("/usr/share/blender/datafiles/studiolights/world/forest.exr")
mapping = world.nodes.new("ShaderNodeMapping")
mapping.vector_type = "POINT"
mapping.inputs["Rotation"].default_value = (0, 0, math.radians(30))
world.links.new(world.nodes.new("ShaderNodeTexCoord").outputs["Generated"], mapping.inputs["Vector"])
world.links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
world.links.new(texture.outputs["Color"], background.inputs["Color"])
background.inputs["Strength"].default_value = 0.5
for shape, size, size_y in (("DISK", 0.5, 0.5), ("ELLIPSE", 0.6, 0.3)):
    lamp = bpy.data.lights.new(shape.title(), "AREA")
    lamp.shape, lamp.size, lamp.size_y, lamp.energy = shape, size, size_y, 20
    obj = bpy.data.objects.new(lamp.name, lamp)
    obj.location = (1, 1, 2.9)
    scene.collection.objects.link(obj)

wrapper, warnings, info, folder = export("hdri")
spec = wrapper.get("world", {})
check(spec.get("image") == "hdri_world.exr" and os.path.isfile(os.path.join(folder, "hdri_world.exr")),
      f"the world image is not copied beside the scene: {spec}")
check(abs(spec.get("rotation_degrees", 0) - 30) < 1e-4 and spec.get("strength") == 0.5, f"world: {spec}")
check("world: image" in info or "hdri_world.exr" in info, f"steadylight info does not list the image:\n{info}")
for emitter in wrapper["objects"]:
    if emitter["name"] not in ("Disk", "Ellipse"):
        continue
    with open(os.path.join(folder, emitter["shape"]["file"])) as f:
        points = [[float(v) for v in line.split()[1:]] for line in f if line.startswith("v ")]
    centre, rim = points[0], points[1:]
    area = 0.0
    for a, b in zip(rim, rim[1:] + rim[:1]):
        u = [a[i] - centre[i] for i in range(3)]
        v = [b[i] - centre[i] for i in range(3)]
        cross = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        area += 0.5 * math.sqrt(sum(c * c for c in cross))
        check(cross[1] < 0, f"{emitter['name']}: a triangle faces up, not down the lamp's -z")
    power = emitter["emission"][0] * area * 4
    check(abs(power - 20) < 1e-3, f"{emitter['name']}: radiance x area x 4 is {power} W, not the lamp's 20 W")

# The same image packed into the .blend: written out beside the scene, byte for byte.
texture.image.pack()
wrapper, warnings, info, folder = export("packed")
with open(os.path.join(folder, "packed_world.exr"), "rb") as written, \
        open("/usr/share/blender/datafiles/studiolights/world/forest.exr", "rb") as original:
    check(written.read() == original.read(), "the packed world image is not written out as it is")
check(wrapper.get("world", {}).get("image") == "packed_world.exr", f"packed: {wrapper.get('world')}")

# Blender's sky.
sky = world.nodes.new("ShaderNodeTexSky")
sky.sky_type = "NISHITA"
sky.sun_elevation, sky.sun_rotation = math.radians(20), math.radians(45)
world.links.new(sky.outputs["Color"], background.inputs["Color"])
wrapper, warnings, info, _ = export("sky")
spec = wrapper.get("world", {}).get("sky", {})
check(abs(spec.get("sun_elevation", 0) - 20) < 1e-4 and abs(spec.get("sun_rotation", 0) - 45) < 1e-4,
      f"sky: {spec}")
check("sky sun" in info, f"steadylight info lists no sky sun:\n{info}")

# A node the export does not carry.
world.links.new(world.nodes.new("ShaderNodeTexNoise").outputs["Color"], background.inputs["Color"])
wrapper, warnings, info, _ = export("noise")
check(any("ShaderNodeTexNoise" in w and "not carried" in w for w in warnings), f"no warning: {warnings}")

# Lamps that move: the area lamp slides and turns, a point lamp rises, over frames 1-3. Frame 3
# of the export must be the export of the room with both standing where frame 3 has them (the
# same random numbers: only the area lamp's corners, placed by its tracks or written in the
# world, may differ in their last bits).
scene.world = bpy.data.worlds.new("Dim")
for obj in [o for o in scene.objects if o.name in ("Disk", "Ellipse")]:
    bpy.data.objects.remove(obj, do_unlink=True)
make_test_room.animate_lamps(scene)
panel, bulb = scene.objects["Panel"], scene.objects["Bulb"]
wrapper, warnings, info, moving_folder = export("moving")
panel_spec = next(o for o in wrapper["objects"] if o["name"] == "Panel")
check("animation" in panel_spec and len(panel_spec["animation"]["translation"]["values"]) == 3,
      f"the moving area lamp has no tracks: {panel_spec}")
check("Panel" in info and "dynamic" in info.split("Panel")[1].split("\n")[0], f"the area lamp is not dynamic:\n{info}")
check("Bulb" in info and "moves" in info.split("Bulb")[1].split("\n")[0], f"the point lamp does not move:\n{info}")
check(not any("animated" in w and "Panel" in w for w in warnings), f"a warning for the moving lamp: {warnings}")
scene.frame_set(3)
for obj in (panel, bulb):
    obj.animation_data_clear()
_, _, _, still_folder = export("still")


def frame_3(folder, name):
    """Frame 3 of an export, path traced with 16 samples a pixel; its pixels' red values."""
    subprocess.run([program, "render", os.path.join(folder, name + ".json"), "--method", "path", "--spp", "16",
                    "--frames", "3", "--exr-type", "float", "--out", os.path.join(folder, "frames"), "--quiet"],
                   check=True)
    channels, _ = exr_file.read_exr(os.path.join(folder, "frames", f"{name}_0003.exr"))
    return channels["R"]


moving, still = frame_3(moving_folder, "moving"), frame_3(still_folder, "still")
difference = sum(abs(a - b) for a, b in zip(moving, still)) / max(sum(still), 1e-9)
check(sum(still) > 0 and difference < 1e-3,
      f"frame 3 of the moving lamps differs from the lamps standing there by {difference:.2%}")

for failure in failures:
    print("FAIL", failure)
print("export_variants:", "failed" if failures else "worlds, round lamps and moving lamps exported as steadylight "
      "reads them")
sys.exit(1 if failures else 0)
