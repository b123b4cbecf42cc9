"""Builds the add-on tests' .blend: a 4 x 4 x 3 m room (Blender's axes, +z up) lit by a sun through
a window in its +x wall (marked by a Cycles portal), a light blue world colour and a square area
lamp under the ceiling, with a red cube that moves across the floor over frames 1-3, 64 x 48
pixels. Runs inside Blender:

    blender -b --factory-startup --python tests/blender/make_test_room.py -- OUT.blend [--moving-lamps WxH]

`--moving-lamps` adds lamps that move (animate_lamps) and renders at W x H: the room of the
Cycles cross-check of moving lamps (docs/truth-suite.md).
"""
import math
import os
import sys

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from make_blender_scene import principled  # noqa: E402 (the Blender room's rough, Specular 0 material)


def box(name, centre, size, mat):
    bpy.ops.mesh.primitive_cube_add(size=1, location=centre)
    obj = bpy.context.object
    obj.name = name
    obj.scale = size
    bpy.ops.object.transform_apply(scale=True)
    obj.data.materials.append(mat)
    return obj


def build(path):
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 64, 48, 100
    scene.render.fps = 24
    scene.frame_start, scene.frame_end = 1, 3

    white, red = principled("White", (0.8, 0.8, 0.8)), principled("Red", (0.8, 0.1, 0.1))
    t = 0.1  # wall thickness
    box("Floor", (0, 0, -t / 2), (4 + 2 * t, 4 + 2 * t, t), white)
    box("Ceiling", (0, 0, 3 + t / 2), (4 + 2 * t, 4 + 2 * t, t), white)
    box("Wall -x", (-2 - t / 2, 0, 1.5), (t, 4, 3), white)
    box("Wall -y", (0, -2 - t / 2, 1.5), (4, t, 3), white)
    box("Wall +y", (0, 2 + t / 2, 1.5), (4, t, 3), white)
    # The +x wall around a window 2 m wide and 1.5 m high, from 0.75 m to 2.25 m up.
    box("Wall +x below", (2 + t / 2, 0, 0.375), (t, 4, 0.75), white)
    box("Wall +x above", (2 + t / 2, 0, 2.625), (t, 4, 0.75), white)
    box("Wall +x left", (2 + t / 2, -1.5, 1.5), (t, 1, 1.5), white)
    box("Wall +x right", (2 + t / 2, 1.5, 1.5), (t, 1, 1.5), white)

    cube = box("Cube", (0, -1, 0.3), (0.6, 0.6, 0.6), red)
    for frame, y in ((1, -1.0), (3, 1.0)):
        cube.location.y = y
        cube.keyframe_insert("location", frame=frame)

    sun = bpy.data.lights.new("Sun", "SUN")
    sun.energy, sun.angle = 3, math.radians(2)
    sun_obj = bpy.data.objects.new("Sun", sun)
    scene.collection.objects.link(sun_obj)
    # From outside the window, down into the room: the light travels along -x and down.
    sun_obj.rotation_euler = Vector((-1, 0.2, -0.6)).to_track_quat("-Z", "Y").to_euler()

    lamp = bpy.data.lights.new("Panel", "AREA")
    lamp.shape, lamp.size, lamp.energy = "SQUARE", 0.8, 10
    lamp_obj = bpy.data.objects.new("Panel", lamp)
    scene.collection.objects.link(lamp_obj)
    lamp_obj.location = (-1, 0, 2.9)  # emits down its -z

    portal = bpy.data.lights.new("Window", "AREA")
    portal.shape, portal.size, portal.size_y = "RECTANGLE", 2, 1.5
    portal.cycles.is_portal = True
    portal_obj = bpy.data.objects.new("Window", portal)
    scene.collection.objects.link(portal_obj)
    portal_obj.location = (2 + t, 0, 1.5)
    # Local x along the window's width (Blender y), -z into the room (-x).
    portal_obj.rotation_euler = Vector((-1, 0, 0)).to_track_quat("-Z", "Z").to_euler()
    portal.size, portal.size_y = 1.5, 2  # local x is now up, local y across

    world = bpy.data.worlds.new("Sky blue")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.4, 0.6, 1.0, 1)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    scene.world = world

    camera = bpy.data.cameras.new("Camera")
    camera.lens = 20
    camera_obj = bpy.data.objects.new("Camera", camera)
    scene.collection.objects.link(camera_obj)
    camera_obj.location = (-1.8, -1.8, 1.6)
    camera_obj.rotation_euler = (Vector((1.5, 1.0, 0.6)) - camera_obj.location).to_track_quat("-Z", "Y").to_euler()
    scene.camera = camera_obj
    bpy.ops.wm.save_as_mainfile(filepath=path)


def animate_lamps(scene):
    """The area lamp slides 2 m and turns by 23 degrees, and a 30 W point lamp rises by 1 m, over
    frames 1-3 (Blender's Bezier keys)."""
    panel = scene.objects["Panel"]
    bulb = bpy.data.objects.new("Bulb", bpy.data.lights.new("Bulb", "POINT"))
    bulb.data.energy, bulb.data.shadow_soft_size = 30, 0
    scene.collection.objects.link(bulb)
    for frame, y, turn, z in ((1, -1.0, 0.0, 1.0), (3, 1.0, 0.4, 2.0)):
        panel.location.y, panel.rotation_euler.x, bulb.location = y, turn, (1, 0, z)
        panel.keyframe_insert("location", frame=frame)
        panel.keyframe_insert("rotation_euler", frame=frame)
        bulb.keyframe_insert("location", frame=frame)


if __name__ == "__main__":
    args = sys.argv[sys.argv.index("--") + 1:]
    build(args[0])
    if "--moving-lamps" in args:
        animate_lamps(bpy.context.scene)
        width, height = args[args.index("--moving-lamps") + 1].split("x")
        bpy.context.scene.render.resolution_x, bpy.context.scene.render.resolution_y = int(width), int(height)
        bpy.ops.wm.save_as_mainfile(filepath=args[0])
