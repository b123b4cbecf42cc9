"""Builds a steadylight JSON scene (docs/scene-format.md) in Blender, so that Cycles can render the
same scene as steadylight (scripts/cycles_reference.py --json SCENE.json). Runs inside Blender.

What it reads, which is what the daylit truth-suite scenes use:
- quads, boxes and spheres (a UV sphere of 128 x 64, smooth shaded), placed by `transform` and
  at the frame's time by linear `translation` tracks;
- lambert materials (Diffuse BSDF, roughness 0) and dielectrics (Glass BSDF, sharp);
- suns: a Sun lamp whose Strength is the irradiance (W m^-2, the largest channel, the colour the
  channels over it) and whose Angle is the sun's angular diameter;
- a world colour: the Background's Color x Strength, Blender's World as steadylight's is;
- a world image: an Environment Texture (equirectangular, Closest: steadylight looks up the
  nearest pixel) fed by a Mapping node of type Point whose Z rotation is `rotation_degrees`,
  into the Background at `strength`;
- portals: Cycles light portals (a rectangular area light marked Portal, facing into the room);
- the camera: position, look_at, up, fov_y (vertical sensor fit) and resolution.
Anything else (emitters, point and spot lamps, a sky, glTF, rotation tracks) stops it with a
message rather than render another scene.

steadylight's frame is glTF's (+y up); Blender's is +z up: (x, y, z) becomes (x, -z, y), a
rotation, so every normal keeps its side.
"""
import json
import math
import os

import bpy
from mathutils import Matrix, Quaternion, Vector


def to_blender(v):
    return Vector((v[0], -v[2], v[1]))


def rotation(spec):
    """A steadylight rotation (axis and degrees, or a quaternion [x, y, z, w]) as a 3x3 matrix."""
    if isinstance(spec, dict):
        return Matrix.Rotation(math.radians(spec["degrees"]), 3, Vector(spec["axis"]).normalized())
    x, y, z, w = spec
    return Quaternion((w, x, y, z)).to_matrix()


def track_at(track, time_s):
    """A linear (or step) track's value at `time_s`, held before the first and after the last key."""
    times, values = track["times"], track["values"]
    if time_s <= times[0]:
        return values[0]
    for i in range(1, len(times)):
        if time_s <= times[i]:
            if track.get("interpolation", "linear") == "step":
                return values[i - 1]
            t = (time_s - times[i - 1]) / (times[i] - times[i - 1])
            return [a + (b - a) * t for a, b in zip(values[i - 1], values[i])]
    return values[-1]


def placement(obj, time_s):
    """The object's world_from_object as (3x3 rotation, translation) in steadylight's frame."""
    rot, offset = Matrix.Identity(3), Vector((0, 0, 0))
    transform = obj.get("transform", {})
    if "rotation" in transform:
        rot = rotation(transform["rotation"])
    if "translation" in transform:
        offset = Vector(transform["translation"])
    animation = obj.get("animation", {})
    if set(animation) - {"translation"}:
        raise SystemExit(f"{obj['name']}: only translation tracks are supported here")
    if "translation" in animation:
        offset = Vector(track_at(animation["translation"], time_s))
    return rot, offset


def box_mesh(center, size):
    """The 8 corners and 6 outward-facing quads of an axis-aligned box."""
    c, h = Vector(center), Vector(size) / 2
    corners = [c + Vector((sx * h.x, sy * h.y, sz * h.z)) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return corners, faces


def add_mesh(name, vertices, faces, material):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(to_blender(v)) for v in vertices], [], faces)
    mesh.update()
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def add_sphere(name, center, radius, material):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=128, ring_count=64, radius=radius, location=to_blender(center))
    obj = bpy.context.active_object
    obj.name = name
    bpy.ops.object.shade_smooth()
    obj.data.materials.append(material)


def make_material(name, spec):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    if spec["type"] == "lambert":
        shader = nodes.new("ShaderNodeBsdfDiffuse")
        r = spec["reflectance"]
        shader.inputs["Color"].default_value = (*([r] * 3 if isinstance(r, (int, float)) else r), 1)
        shader.inputs["Roughness"].default_value = 0.0
    elif spec["type"] == "dielectric":
        shader = nodes.new("ShaderNodeBsdfGlass")
        shader.distribution = "SHARP"
        shader.inputs["IOR"].default_value = spec.get("ior", 1.5)
    else:
        raise SystemExit(f"material {name}: type {spec['type']} is not supported here")
    links.new(shader.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
    return material


def add_objects(scene, time_s):
    materials = {name: make_material(name, spec) for name, spec in scene.get("materials", {}).items()}
    for obj in scene["objects"]:
        if "emission" in obj or "animation" in obj and "emission" in obj["animation"]:
            raise SystemExit(f"{obj['name']}: emitters are not supported here")
        shape, material = obj["shape"], materials[obj["material"]]
        rot, offset = placement(obj, time_s)
        place = lambda p: rot @ Vector(p) + offset  # noqa: E731
        if shape["type"] == "quad":
            c, u, v = Vector(shape["corner"]), Vector(shape["edge_u"]), Vector(shape["edge_v"])
            add_mesh(obj["name"], [place(p) for p in (c, c + u, c + u + v, c + v)], [(0, 1, 2, 3)], material)
        elif shape["type"] == "box":
            corners, faces = box_mesh(shape["center"], shape["size"])
            add_mesh(obj["name"], [place(p) for p in corners], faces, material)
        elif shape["type"] == "sphere":
            add_sphere(obj["name"], place(shape.get("center", [0, 0, 0])), shape["radius"], material)
        else:
            raise SystemExit(f"{obj['name']}: shape {shape['type']} is not supported here")


def add_suns(scene):
    for light in scene.get("lights", []):
        if light["type"] != "sun":
            raise SystemExit(f"light {light.get('name')}: only suns are supported here")
        irradiance = light["irradiance"]
        rgb = [irradiance] * 3 if isinstance(irradiance, (int, float)) else irradiance
        strength = max(rgb)
        data = bpy.data.lights.new(light.get("name", "sun"), "SUN")
        data.energy = strength
        data.color = [c / strength for c in rgb]
        data.angle = math.radians(light.get("angle_degrees", 0.53))
        obj = bpy.data.objects.new(data.name, data)
        # A Sun lamp shines along its local -z.
        obj.rotation_euler = to_blender(light["direction"]).normalized().to_track_quat("-Z", "Y").to_euler()
        bpy.context.scene.collection.objects.link(obj)


def add_world_image(world, spec, folder):
    """The Background's colour from the image as steadylight maps it (docs/scene-format.md)."""
    nodes, links = world.node_tree.nodes, world.node_tree.links
    coordinates = nodes.new("ShaderNodeTexCoord")
    mapping = nodes.new("ShaderNodeMapping")
    mapping.vector_type = "POINT"
    mapping.inputs["Rotation"].default_value = (0, 0, math.radians(spec.get("rotation_degrees", 0)))
    texture = nodes.new("ShaderNodeTexEnvironment")
    texture.image = bpy.data.images.load(os.path.join(folder, spec["image"]))
    texture.image.colorspace_settings.name = "Linear"
    texture.interpolation = "Closest"
    texture.projection = "EQUIRECTANGULAR"
    links.new(coordinates.outputs["Generated"], mapping.inputs["Vector"])
    links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
    links.new(texture.outputs["Color"], nodes["Background"].inputs["Color"])


def add_world(scene, folder):
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    spec = scene.get("world")
    if spec and "sky" in spec:
        raise SystemExit("world: a sky is not supported here")
    if spec and "image" in spec:
        add_world_image(world, spec, folder)
        background.inputs["Strength"].default_value = spec.get("strength", 1)
        bpy.context.scene.world = world
        return
    colour = spec.get("color", [0.05] * 3) if spec else [0, 0, 0]
    colour = [colour] * 3 if isinstance(colour, (int, float)) else colour
    background.inputs["Color"].default_value = (*colour, 1)
    background.inputs["Strength"].default_value = spec.get("strength", 1) if spec else 0
    bpy.context.scene.world = world


def add_portals(scene):
    for i, portal in enumerate(scene.get("portals", [])):
        u, v = to_blender(portal["edge_u"]), to_blender(portal["edge_v"])
        data = bpy.data.lights.new(f"portal{i}", "AREA")
        data.shape = "RECTANGLE"
        data.size, data.size_y = v.length, u.length
        data.cycles.is_portal = True
        obj = bpy.data.objects.new(data.name, data)
        # Local x along edge_v and y along edge_u, so that -z, the way it faces, is edge_u x edge_v: into the room.
        x, y = v.normalized(), u.normalized()
        obj.matrix_world = Matrix.Translation(to_blender(portal["corner"]) + (u + v) / 2) @ \
            Matrix((x, y, x.cross(y))).transposed().to_4x4()
        bpy.context.scene.collection.objects.link(obj)


def add_camera(scene, size):
    spec = scene["camera"]
    if "animation" in spec:
        raise SystemExit("camera: animated cameras are not supported here")
    data = bpy.data.cameras.new("Camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(spec["fov_y"])
    obj = bpy.data.objects.new("Camera", data)
    position, target = to_blender(spec["position"]), to_blender(spec["look_at"])
    obj.location = position
    obj.rotation_euler = (target - position).to_track_quat("-Z", "Y").to_euler()
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.scene.camera = obj
    width, height = size or spec["resolution"]
    bpy.context.scene.render.resolution_x, bpy.context.scene.render.resolution_y = width, height
    bpy.context.scene.render.resolution_percentage = 100


def build_scene(path, frame, size=None):
    """Empties Blender's factory scene and builds `path`'s scene at `frame` (time frame / fps)."""
    with open(path) as f:
        scene = json.load(f)
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    fps = scene.get("frames", {}).get("fps", 24)
    add_objects(scene, frame / fps)
    add_suns(scene)
    add_world(scene, os.path.dirname(os.path.abspath(path)))
    add_portals(scene)
    add_camera(scene, size)
