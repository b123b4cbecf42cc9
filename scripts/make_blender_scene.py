"""Builds the truth suite's Blender room in Blender itself and exports it with Blender's own glTF
exporter, so that `scenes/blender_room.glb` is what a user's Blender writes (docs/truth-suite.md).

Run headless:  blender -b --factory-startup --python scripts/make_blender_scene.py -- OUT.glb [--blend OUT.blend]

The scene (Blender's Z-up metres; the exporter turns it into glTF's Y-up):
- an L-shaped room 2.7 m high: arm A is [0,6] x [0,3], arm B is [3,6] x [3,6], closed by a floor,
  a ceiling and six walls (arm A's end wall green, arm B's end wall blue). Unlike BALL's and
  TABLE's boxes it is not convex: the inner corner hides each arm's far end from the other
  arm's light;
- two wall lights, each a closed fixture box whose front face emits (Principled Emission x
  Emission Strength): one on arm A's long wall, one on arm B's outer wall, both outside the
  camera's view, so that no emitter is seen directly;
- a static yellow ball (smooth shaded: interpolated shading normals) and a white plinth;
- a red crate carried by an empty ("Cart", translation keys) and turning inside it (rotation keys
  on the crate): an animated node below an animated node. It moves from arm A through the
  elbow into arm B over frames 0-30 at 24 fps;
- a camera in the elbow's outer corner, which sees down both arms: 320 x 240, fov_y 60 degrees,
  with a vertical sensor fit, so glTF's yfov is the camera's angle.

Every surface is a Principled BSDF with Metallic 0, Roughness 1 and Specular 0, which steadylight
renders as Lambert with the base colour under a coat that reflects only at grazing angles; emitters have a black base colour so that they
reflect nothing in either renderer. Cycles still shades Principled's diffuse lobe with Disney's
retro-reflection at Roughness 1; scripts/cycles_reference.py --lambert swaps in a Diffuse BSDF.

The export samples the animation at every frame from frame 0 (key times frame / 24 s, so
steadylight's frame f is Blender's frame f), with cameras, without punctual lights (there are
none), +Y up.
"""
import math
import sys

import bpy
from mathutils import Vector

FPS = 24
FRAME_END = 30
RESOLUTION = (320, 240)
HEIGHT = 2.7
LAMP_STRENGTH = 15.0  # Principled Emission Strength: emitted radiance in W m^-2 sr^-1 per unit colour

COLOURS = {
    "Floor": (0.55, 0.45, 0.35),
    "Ceiling": (0.80, 0.80, 0.80),
    "Wall": (0.75, 0.74, 0.70),
    "Green Wall": (0.30, 0.55, 0.30),
    "Blue Wall": (0.25, 0.40, 0.70),
    "Crate": (0.75, 0.12, 0.08),
    "Ball": (0.80, 0.65, 0.15),
    "Housing": (0.50, 0.50, 0.50),
}


def clear_scene():
    """Remove the factory startup's cube, lamp and camera, and everything they used."""
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for collection in (bpy.data.meshes, bpy.data.materials, bpy.data.cameras, bpy.data.lights):
        for block in list(collection):
            collection.remove(block)


def principled(name, colour, emission=None, strength=1.0):
    """A Principled BSDF material: a rough dielectric with Specular 0, maybe emitting."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Metallic"].default_value = 0.0
    bsdf.inputs["Roughness"].default_value = 1.0
    bsdf.inputs["Specular"].default_value = 0.0
    if emission:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
    return material


def mesh_object(name, vertices, faces, materials, face_materials=None, smooth=False):
    """A mesh object from vertices and faces (counter-clockwise seen from the side they face)."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(vertices, [], faces)
    for material in materials:
        mesh.materials.append(material)
    for polygon, index in zip(mesh.polygons, face_materials or [0] * len(faces)):
        polygon.material_index = index
        polygon.use_smooth = smooth
    mesh.validate()
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def box(name, size, materials, face_materials=None, location=(0, 0, 0)):
    """An axis-aligned box centred on its origin with outward faces (-x +x -y +y -z +z)."""
    sx, sy, sz = (s / 2 for s in size)
    v = [(x, y, z) for x in (-sx, sx) for y in (-sy, sy) for z in (-sz, sz)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    obj = mesh_object(name, v, faces, materials, face_materials)
    obj.location = location
    return obj


def smooth_sphere(name, radius, location, material, segments=12, rings=6):
    """A smooth-shaded UV sphere (interpolated shading normals) with one material."""
    bpy.ops.mesh.primitive_uv_sphere_add(segments=segments, ring_count=rings, radius=radius, location=location)
    ball = bpy.context.active_object
    ball.name = name
    ball.data.materials.append(material)
    bpy.ops.object.shade_smooth()
    return ball


def walls(name, outline, height, materials, slots=None):
    """Walls along `outline` (x, y corners walked counter-clockwise seen from above, so that each
    wall faces the inside, its left), from the floor to `height`, one quad each."""
    vertices, faces = [], []
    for a, b in zip(outline, outline[1:] + outline[:1]):
        n = len(vertices)
        vertices += [(*a, 0), (*a, height), (*b, height), (*b, 0)]
        faces.append((n, n + 1, n + 2, n + 3))
    return mesh_object(name, vertices, faces, materials, slots)


def build_room(mat):
    """Floor, ceiling (three quads each, sharing vertices) and the six walls of the L."""
    grid = [(0, 0), (3, 0), (6, 0), (0, 3), (3, 3), (6, 3), (3, 6), (6, 6)]
    cells = [(0, 1, 4, 3), (1, 2, 5, 4), (4, 5, 7, 6)]  # counter-clockwise seen from above
    mesh_object("Floor", [(x, y, 0) for x, y in grid], cells, [mat["Floor"]])
    mesh_object("Ceiling", [(x, y, HEIGHT) for x, y in grid], [tuple(reversed(c)) for c in cells],
                [mat["Ceiling"]])
    # The outline walked counter-clockwise seen from above: each wall faces the inside (its left).
    outline = [(0, 0), (3, 0), (6, 0), (6, 3), (6, 6), (3, 6), (3, 3), (0, 3)]
    slots = [0, 0, 0, 0, 2, 0, 0, 1]  # (6,6)-(3,6) blue: arm B's end; (0,3)-(0,0) green: arm A's end
    walls("Walls", outline, HEIGHT, [mat["Wall"], mat["Green Wall"], mat["Blue Wall"]], slots)


def build_lights(mat):
    """Two closed fixtures, 6 cm deep, whose 1.0 m x 0.7 m front face emits into the room."""
    fixtures = (("Lamp A", (1.5, 0.03, 1.95), (1.0, 0.06, 0.7), 3),   # arm A's long wall, facing +y
                ("Lamp B", (5.97, 4.8, 1.95), (0.06, 1.0, 0.7), 0))   # arm B's outer wall, facing -x
    for name, location, size, front in fixtures:
        slots = [1] * 6
        slots[front] = 0  # slot 0 = Lamp, slot 1 = Housing
        box(name, size, [mat["Lamp"], mat["Housing"]], slots, location)


def build_props(mat):
    """The static ball and plinth."""
    smooth_sphere("Ball", 0.35, (1.2, 2.4, 0.35), mat["Ball"])
    box("Plinth", (0.4, 0.4, 1.0), [mat["Wall"]], location=(3.45, 4.9, 0.5))


def key(obj, path, frame, value):
    setattr(obj, path, value)
    obj.keyframe_insert(data_path=path, frame=frame)


def build_crate(mat):
    """The cart (an empty, translated) carries the crate (rotated about its vertical axis)."""
    cart = bpy.data.objects.new("Cart", None)
    bpy.context.scene.collection.objects.link(cart)
    crate = box("Crate", (0.5, 0.5, 0.5), [mat["Crate"]], location=(0, 0, 0.25))
    crate.parent = cart
    path = [(0, (1.5, 1.4, 0)), (12, (3.9, 1.5, 0)), (24, (4.5, 3.6, 0)), (30, (4.6, 4.4, 0))]
    for frame, location in path:
        key(cart, "location", frame, location)
    for frame, degrees in ((0, 0), (30, 135)):
        key(crate, "rotation_euler", frame, (0, 0, math.radians(degrees)))


def build_camera(location=(5.7, 0.3, 1.8), target=(2.8, 3.2, 0.6), fov_y_deg=60):
    """A camera at `location` looking at `target` (by default in the outer corner of the elbow,
    which sees down both arms), fov_y with a vertical sensor fit."""
    data = bpy.data.cameras.new("Camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(fov_y_deg)
    camera = bpy.data.objects.new("Camera", data)
    bpy.context.scene.collection.objects.link(camera)
    camera.location = location
    direction = Vector(target) - camera.location
    camera.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
    bpy.context.scene.camera = camera


def set_up_scene(frame_end, resolution):
    """Clears the startup file and sets the frame rate (FPS), the frames 0..frame_end and the resolution."""
    clear_scene()
    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = FPS, 1.0
    scene.frame_start, scene.frame_end = 0, frame_end
    scene.render.resolution_x, scene.render.resolution_y = resolution
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0
    return scene


def build_scene():
    """The whole scene in the current Blender file, at frame 0."""
    scene = set_up_scene(FRAME_END, RESOLUTION)
    mat = {name: principled(name, colour) for name, colour in COLOURS.items()}
    mat["Lamp"] = principled("Lamp", (0, 0, 0), emission=(1.0, 0.9, 0.75), strength=LAMP_STRENGTH)
    build_room(mat)
    build_lights(mat)
    build_props(mat)
    build_crate(mat)
    build_camera()
    scene.frame_set(0)


def export_glb(path, textures=False):
    """A GLB, +Y up, with cameras and animations sampled every frame; texture coordinates (and
    the images, packed) only with `textures`; no tangents (steadylight makes them)."""
    bpy.ops.export_scene.gltf(
        filepath=path, export_format="GLB", export_yup=True, export_apply=True,
        export_cameras=True, export_lights=False, export_extras=False,
        export_animations=True, export_force_sampling=True, export_frame_range=True,
        export_frame_step=1, export_optimize_animation_size=False,
        export_texcoords=textures, export_normals=True, export_tangents=False, export_colors=False)


def main(argv, build=build_scene, textures=False, usage=__doc__):
    """Builds the scene with `build`, exports it to the path after `--`, and saves the .blend too
    with `--blend PATH`."""
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    if len(args) not in (1, 3) or (len(args) == 3 and args[1] != "--blend"):
        sys.exit(usage)
    build()
    export_glb(args[0], textures)
    if len(args) == 3:
        bpy.ops.wm.save_as_mainfile(filepath=args[2])


if __name__ == "__main__":
    main(sys.argv)
