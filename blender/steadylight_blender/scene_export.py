"""The scene as Blender has it, written for steadylight: a .glb by Blender's own glTF exporter and
a wrapper JSON beside it for what glTF does not carry (docs/blender.md, "What is exported").

Runs in a child `blender -b` on a copy of the .blend (scene_export_main.py), never in the
artist's session: the exporter changes the current frame as it samples animations, which is not
safe while Blender renders, and the copy may be edited freely (cameras other than the scene's
are removed so that the .glb has one).

Axes: Blender is +z up, glTF and steadylight +y up; Blender's (x, y, z) is steadylight's
(x, z, -y), a rotation, so every normal keeps its side.
"""
import json
import math
import os
import shutil

import bpy
from mathutils import Matrix, Quaternion, Vector

# Cycles gives an area lamp of power P watts and area A the radiance P / (4 A) (measured: a 1 m
# square of 10 W seen head-on reads 2.5; its light on a white floor agrees), not P / (pi A).
AREA_LAMP_RADIANCE_PER_WATT_AREA = 0.25
# Segments of the polygon a disc or ellipse lamp becomes; its radiance keeps the lamp's power.
DISC_SEGMENTS = 32

# Nodes a material may hold that the glTF exporter bakes into the material it writes
# (docs/gltf.md, "Exporting from Blender"); any other node is reported, not dropped silently.
MATERIAL_NODES = {
    "OUTPUT_MATERIAL", "BSDF_PRINCIPLED", "TEX_IMAGE", "NORMAL_MAP", "SEPRGB", "SEPARATE_COLOR",
    "COMBRGB", "COMBINE_COLOR", "MAPPING", "TEX_COORD", "UVMAP", "EMISSION", "VOLUME_ABSORPTION",
    "GROUP", "FRAME", "REROUTE", "MIX_SHADER", "ADD_SHADER", "BSDF_TRANSPARENT", "MIX_RGB", "MIX",
    "VERTEX_COLOR", "ATTRIBUTE",
}


def to_steadylight(v):
    return [v[0], v[2], -v[1]]


# The same turn as a rotation (-90 degrees about x), which placements are composed with.
TO_STEADYLIGHT = Quaternion((1, 0, 0), -math.pi / 2)


def rounded(values, digits=6):
    return [round(float(v), digits) for v in values]


class Export:
    """What one export writes beside its .glb and JSON, and what it could not carry."""

    def __init__(self, name):
        self.name = name
        self.warnings = []
        self.files = {}  # file name -> its bytes (disc and ellipse lamps' OBJs, a packed world image)
        self.copies = {}  # file name -> the file copied there (the world image)

    def warn(self, message):
        self.warnings.append(message)


def world_spec(world, export):
    """The world as steadylight's "world" key, or None for none (docs/scene-format.md, "World")."""
    if world is None:
        return None
    if not world.use_nodes or world.node_tree is None:
        return {"color": rounded(world.color), "strength": 1}
    nodes = world.node_tree.nodes
    output = next((n for n in nodes if n.type == "OUTPUT_WORLD" and n.is_active_output), None)
    if output is None or not output.inputs["Surface"].is_linked:
        return None
    background = output.inputs["Surface"].links[0].from_node
    if background.type != "BACKGROUND":
        export.warn(f"world {world.name}: a {background.bl_idname} into the World Output is not carried "
                    "(only a Background shader is): the world is left black")
        return None
    strength_input = background.inputs["Strength"]
    if strength_input.is_linked:
        export.warn(f"world {world.name}: a node into the Background's Strength is not carried: its value "
                    f"{strength_input.default_value:g} is used")
    strength = float(strength_input.default_value)
    color_input = background.inputs["Color"]
    if not color_input.is_linked:
        return {"color": rounded(color_input.default_value[:3]), "strength": strength}
    source = color_input.links[0].from_node
    if source.type == "TEX_ENVIRONMENT":
        return environment_spec(world, source, strength, export)
    if source.type == "TEX_SKY":
        return sky_spec(world, source, strength, export)
    export.warn(f"world {world.name}: a {source.bl_idname} into the Background's Color is not carried "
                f"(an Environment Texture or a Sky Texture is): its colour "
                f"{rounded(color_input.default_value[:3], 3)} is used")
    return {"color": rounded(color_input.default_value[:3]), "strength": strength}


def environment_spec(world, texture, strength, export):
    if texture.image is None:
        export.warn(f"world {world.name}: the Environment Texture has no image: the world is left black")
        return None
    if texture.projection != "EQUIRECTANGULAR":
        export.warn(f"world {world.name}: a {texture.projection.lower()} Environment Texture is read as "
                    "equirectangular")
    image = texture.image
    path = bpy.path.abspath(image.filepath, library=image.library)
    if image.packed_file is None and not os.path.isfile(path):
        export.warn(f"world {world.name}: the image {image.name} is missing ({path}): the world is left black")
        return None
    rotation = 0.0
    vector = texture.inputs["Vector"]
    if vector.is_linked:
        mapping = vector.links[0].from_node
        if mapping.type == "MAPPING" and mapping.vector_type == "POINT":
            rx, ry, rz = mapping.inputs["Rotation"].default_value
            location = mapping.inputs["Location"].default_value
            scale = mapping.inputs["Scale"].default_value
            if abs(rx) > 1e-6 or abs(ry) > 1e-6 or any(abs(v) > 1e-6 for v in location) \
                    or any(abs(v - 1) > 1e-6 for v in scale):
                export.warn(f"world {world.name}: only the Mapping node's Z rotation is carried, not its "
                            "location, scale or X and Y rotations")
            rotation = math.fmod(math.degrees(rz), 360)  # steadylight takes [-360, 360]
        else:
            export.warn(f"world {world.name}: a {mapping.bl_idname} into the Environment Texture's Vector is "
                        "not carried (a Mapping node of type Point is)")
    # Copied beside the scene, so that the folder renders anywhere (a farm's workers confine
    # their inputs to the scene file's folder).
    extension = {"OPEN_EXR": ".exr", "OPEN_EXR_MULTILAYER": ".exr", "HDR": ".hdr"}.get(image.file_format)
    if extension is None:
        export.warn(f"world {world.name}: the image {image.name} is {image.file_format}; steadylight reads "
                    "OpenEXR and Radiance HDR world images: the world is left black")
        return None
    file_name = export.name + "_world" + extension
    if image.packed_file is not None:
        export.files[file_name] = bytes(image.packed_file.data)
    else:
        export.copies[file_name] = os.path.abspath(path)
    return {"image": file_name, "strength": strength, "rotation_degrees": round(rotation, 6)}


def sky_spec(world, sky, strength, export):
    if sky.sky_type != "NISHITA":
        export.warn(f"world {world.name}: a {sky.sky_type.title()} Sky Texture is not carried (Nishita is): "
                    "the world is left black")
        return None
    return {"sky": {"model": "nishita",
                    "sun_elevation": math.degrees(sky.sun_elevation),
                    "sun_rotation": math.degrees(sky.sun_rotation),
                    "sun_size": math.degrees(sky.sun_size),
                    "sun_intensity": sky.sun_intensity,
                    "sun_disc": bool(sky.sun_disc),
                    "altitude": sky.altitude,
                    "air_density": sky.air_density,
                    "dust_density": sky.dust_density,
                    "ozone_density": sky.ozone_density},
            "strength": strength}


def lamp_frame(obj, matrix):
    """An area lamp's centre and its local x and y edges as long as the lamp, placed by `matrix`
    (the world's: in Blender's axes; the identity: in the lamp's own)."""
    lamp = obj.data
    size_x = lamp.size
    size_y = lamp.size_y if lamp.shape in ("RECTANGLE", "ELLIPSE") else lamp.size
    x = matrix.to_3x3() @ Vector((size_x, 0, 0))
    y = matrix.to_3x3() @ Vector((0, size_y, 0))
    return matrix.translation.copy(), x, y


def portal_spec(obj):
    """A Cycles portal (an area lamp marked Portal; it faces down its -z, into the room)."""
    centre, x, y = lamp_frame(obj, obj.matrix_world)
    # edge_u x edge_v must face into the room: y x x is the lamp's -z.
    return {"corner": rounded(to_steadylight(centre - (x + y) / 2)),
            "edge_u": rounded(to_steadylight(y)), "edge_v": rounded(to_steadylight(x))}


def world_matrices(scene, objects):
    """Each object's world matrix at every frame of the scene (frame_start to frame_end)."""
    current = scene.frame_current
    matrices = {obj.name: [] for obj in objects}
    for frame in range(scene.frame_start, scene.frame_end + 1):
        scene.frame_set(frame)
        for obj in objects:
            matrices[obj.name].append(obj.matrix_world.copy())
    scene.frame_set(current)
    return matrices


def motion_tracks(scene, matrices, obj, export):
    """An object's placement at every frame as steadylight's translation, rotation and scale tracks
    (one key per frame, at frame / fps as the glTF exporter writes them), its shape in its own axes."""
    times = [round(f / scene.render.fps, 6) for f in range(scene.frame_start, scene.frame_end + 1)]
    translations, rotations, scales = [], [], []
    for matrix in matrices:
        translation, rotation, scale = matrix.decompose()
        turned = TO_STEADYLIGHT @ rotation
        translations.append(rounded(to_steadylight(translation)))
        rotations.append(rounded([turned.x, turned.y, turned.z, turned.w]))
        scales.append(rounded(scale))
    if any(s != scales[0] for s in scales):
        export.warn(f"area lamp {obj.name}: its size changes, and its radiance stays the first frame's (its power "
                    "changes with its size)")
    return {"translation": {"times": times, "values": translations},
            "rotation": {"times": times, "values": rotations},
            "scale": {"times": times, "values": scales}}


def area_lamp_object(obj, export, motion=None):
    """An area lamp as an emitting quad or polygon mesh of the lamp's radiance, emitting down its -z;
    with `motion` (its tracks), in the lamp's own axes, moved by them."""
    lamp = obj.data
    _, x, y = lamp_frame(obj, obj.matrix_world)
    area = x.length * y.length * (math.pi / 4 if lamp.shape in ("DISK", "ELLIPSE") else 1)
    if area <= 0 or lamp.energy <= 0 or max(lamp.color) <= 0:
        return None  # no light, and Blender's lamps are not seen nor cast shadows
    if not obj.visible_camera:
        export.warn(f"area lamp {obj.name}: the camera sees it, and it casts shadows (it becomes an emitting "
                    "surface), where Blender's lamp is hidden from the camera and from shadow rays")
    if lamp.use_nodes:
        export.warn(f"area lamp {obj.name}: its light nodes are not carried (its colour and power are)")
    if abs(math.degrees(lamp.spread) - 180) > 0.01:
        export.warn(f"area lamp {obj.name}: its Spread ({math.degrees(lamp.spread):.0f} degrees) is not "
                    "carried: it emits into the whole half-space")
    radiance = [c * lamp.energy * AREA_LAMP_RADIANCE_PER_WATT_AREA / area for c in lamp.color]
    # A moving lamp's shape is in its own axes, which its tracks place; a still one's in the world.
    centre, x, y = lamp_frame(obj, Matrix.Identity(4) if motion else obj.matrix_world)
    axes = (lambda v: list(v)) if motion else to_steadylight
    if lamp.shape in ("SQUARE", "RECTANGLE"):
        shape = {"type": "quad", "corner": rounded(axes(centre - (x + y) / 2)),
                 "edge_u": rounded(axes(y)), "edge_v": rounded(axes(x))}
    else:
        # A fan of triangles, wound clockwise seen from +z so that its front is the lamp's -z; its
        # radiance raised by the area the polygon misses, so that it keeps the lamp's power.
        points = [centre + x * (0.5 * math.cos(-2 * math.pi * i / DISC_SEGMENTS))
                  + y * (0.5 * math.sin(-2 * math.pi * i / DISC_SEGMENTS)) for i in range(DISC_SEGMENTS)]
        polygon_area = DISC_SEGMENTS / 2 * math.sin(2 * math.pi / DISC_SEGMENTS) * x.length * y.length / 4
        radiance = [r * area / polygon_area for r in radiance]
        file_name = f"{export.name}_lamp{sum(name.endswith('.obj') for name in export.files)}.obj"
        lines = [f"v {' '.join(f'{c:.6f}' for c in axes(p))}" for p in [centre] + points]
        lines += [f"f 1 {i + 2} {(i + 1) % DISC_SEGMENTS + 2}" for i in range(DISC_SEGMENTS)]
        export.files[file_name] = ("\n".join(lines) + "\n").encode()
        shape = {"type": "mesh", "file": file_name}
    spec = {"name": obj.name, "shape": shape, "emission": rounded(radiance)}
    if motion:
        spec["animation"] = motion
    return spec


def lamp_specs(scene, export):
    """Suns' angles by node name, area lamps as emitters, portals; warnings for what is not carried.
    Point, spot and sun lamps that move are moved by the .glb's animation of their nodes; area
    lamps that move (by their own keys, a parent's or a constraint) get tracks of their own."""
    sun_angles, emitters, portals = {}, [], []
    lamps = [obj for obj in scene.objects if obj.type == "LIGHT" and not obj.hide_render]
    area_lamps = [obj for obj in lamps if obj.data.type == "AREA"]
    matrices = world_matrices(scene, area_lamps) if area_lamps else {}
    for obj in lamps:
        lamp = obj.data
        if lamp.animation_data is not None and lamp.animation_data.action is not None:
            export.warn(f"lamp {obj.name}: its animated power, colour or size are not carried: they stay the "
                        "first frame's (its movement is carried)")
        moving = lamp.type == "AREA" and any(m != matrices[obj.name][0] for m in matrices[obj.name])
        if lamp.type == "SUN":
            sun_angles[obj.name] = round(math.degrees(lamp.angle), 6)
        elif lamp.type == "AREA":
            if lamp.cycles.is_portal:
                if moving:
                    export.warn(f"portal {obj.name}: a portal that moves stays where it is at the current frame")
                portals.append(portal_spec(obj))
            else:
                motion = motion_tracks(scene, matrices[obj.name], obj, export) if moving else None
                emitter = area_lamp_object(obj, export, motion)
                if emitter is not None:
                    emitters.append(emitter)
        elif lamp.type in ("POINT", "SPOT") and lamp.shadow_soft_size > 0:
            export.warn(f"lamp {obj.name}: its Radius ({lamp.shadow_soft_size:g} m) is not carried: a point "
                        "light, with hard shadows")
    return sun_angles, emitters, portals


def unsupported_features(scene, export):
    """Warnings for what Blender renders and steadylight does not."""
    layers = [layer.name for layer in scene.view_layers if layer.use]
    if len(layers) > 1:
        export.warn(f"view layers {', '.join(layers[1:])}: only the first, {layers[0]}, is rendered (steadylight "
                    "renders the whole scene once)")
    if scene.render.use_motion_blur:
        export.warn("motion blur is not carried: frames are rendered at their instant")
    camera = scene.camera
    if camera is not None and camera.data.dof.use_dof:
        export.warn(f"camera {camera.name}: depth of field is not carried (a pinhole camera)")
    if camera is not None and camera.data.type != "PERSP":
        export.warn(f"camera {camera.name}: a {camera.data.type.lower()} camera is exported as glTF writes it "
                    "(steadylight renders perspective cameras)")
    for obj in scene.objects:
        if obj.hide_render:
            continue
        if obj.type == "VOLUME":
            export.warn(f"object {obj.name}: volumes are not carried")
        if any(modifier.type == "PARTICLE_SYSTEM" for modifier in obj.modifiers):
            export.warn(f"object {obj.name}: particle systems and hair are not carried")
    for material in bpy.data.materials:
        if material.users == 0 or not material.use_nodes or material.node_tree is None:
            continue
        extra = sorted({n.bl_idname for n in material.node_tree.nodes if n.type not in MATERIAL_NODES})
        if extra:
            export.warn(f"material {material.name}: nodes the glTF exporter does not bake ({', '.join(extra)}) "
                        "are not carried")


def keep_only_the_scene_camera(scene):
    """Removes every camera but the scene's from the copy, so that the .glb holds that one."""
    for obj in list(bpy.data.objects):
        if obj.type == "CAMERA" and obj != scene.camera:
            bpy.data.objects.remove(obj, do_unlink=True)


def resolution(scene):
    render = scene.render
    return [max(1, render.resolution_x * render.resolution_percentage // 100),
            max(1, render.resolution_y * render.resolution_percentage // 100)]


def export_scene(scene, folder, name):
    """Writes <folder>/<name>.glb and <folder>/<name>.json; returns the Export (its warnings)."""
    export = Export(name)
    if scene.camera is None:
        raise RuntimeError("the scene has no camera")
    keep_only_the_scene_camera(scene)
    unsupported_features(scene, export)
    os.makedirs(folder, exist_ok=True)
    glb = os.path.join(folder, name + ".glb")
    bpy.ops.export_scene.gltf(filepath=glb, export_format="GLB", use_active_scene=True, use_renderable=True,
                              export_cameras=True, export_lights=True, export_apply=True, export_yup=True,
                              export_animations=True, export_force_sampling=True, export_frame_range=True,
                              export_frame_step=1, export_optimize_animation_size=False,
                              export_current_frame=False, export_extras=False)
    # The exporter writes key times as frame / render.fps (it ignores fps_base): frame f of the
    # wrapper is then Blender's frame f.
    wrapper = {
        "name": name,
        "gltf": name + ".glb",
        "frames": {"fps": scene.render.fps, "count": scene.frame_end + 1},
        "camera": {"resolution": resolution(scene)},
    }
    world = world_spec(scene.world, export)
    if world is not None:
        wrapper["world"] = world
    sun_angles, emitters, portals = lamp_specs(scene, export)
    if sun_angles:
        wrapper["sun_angles_degrees"] = sun_angles
    if emitters:
        wrapper["objects"] = emitters
    if portals:
        wrapper["portals"] = portals
    for file_name, source in export.copies.items():
        shutil.copyfile(source, os.path.join(folder, file_name))
    for file_name, data in export.files.items():
        with open(os.path.join(folder, file_name), "wb") as f:
            f.write(data)
    with open(os.path.join(folder, name + ".json"), "w") as f:
        json.dump(wrapper, f, indent=2)
    return export
