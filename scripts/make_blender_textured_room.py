"""Builds the truth suite's textured Blender room in Blender itself and exports it with Blender's
own glTF exporter, textures packed into the .glb (docs/truth-suite.md, "The textured Blender room").

Run headless:  blender -b --factory-startup --python scripts/make_blender_textured_room.py -- OUT.glb [--blend OUT.blend]

A 5 m x 4 m room, 2.7 m high (Blender's Z-up metres; the exporter turns it into glTF's Y-up),
furnished with what a user's interior brings, every material a Principled BSDF:
- a plank floor: a base colour image (sRGB) tiled 3 x 3 through a Mapping node (which the
  exporter writes as KHR_texture_transform), Roughness 0.45, Specular 0.5 (a rough plastic);
- plastered walls with a tiled normal map (Normal Map node; the exporter writes no tangents);
- a white ceiling with an emissive panel (the light, outside the camera's view);
- a gold metal ball (Metallic 1, Roughness 0.3) and a table whose top has a metallic-roughness
  image (Separate Color: green to Roughness, blue to Metallic): metal stripes on wood. (With the
  legacy Separate RGB node instead, Blender 3.4's exporter writes that image as zeros);
- a cut-out screen: a base colour image whose alpha is 0 in round holes, Blend Mode "Alpha
  Clip" (glTF alpha MASK, cutoff 0.5), which light and shadows pass through;
- a chequered crate (image with nearest filtering, a Closest image node) that slides across
  the floor over frames 0-24 at 24 fps: the moving object;
- a camera in a corner, 320 x 240, fov_y 55 degrees.
Images are made here, pixel by pixel (no files outside the script), and packed as PNG.

It reuses scripts/make_blender_scene.py's helpers (set_up_scene, mesh_object, box, key, export_glb, main).
"""
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_blender_scene as base  # noqa: E402  (Blender's --python puts nothing on sys.path)

FRAME_END = 24
RESOLUTION = (320, 240)
W, D, H = 5.0, 4.0, 2.7


def image(name, size, pixel):
    """A packed PNG image of size x size; pixel(x, y) gives (r, g, b, a) in [0, 1], sRGB-encoded for colour."""
    img = bpy.data.images.new(name, size, size, alpha=True)
    px = []
    for y in range(size):
        for x in range(size):
            px.extend(pixel(x, y))
    img.pixels = px
    img.file_format = "PNG"
    img.pack()
    return img


def planks(x, y):
    row = y // 16
    shade = 0.55 + 0.08 * math.sin(row * 2.3) + 0.04 * math.sin(x * 0.4 + row)
    seam = (y % 16 == 0) or ((x + row * 23) % 64 == 0)
    s = 0.25 if seam else shade
    return (s, s * 0.72, s * 0.48, 1.0)


def bumps(x, y):
    """A tangent-space normal map of soft dimples (x, y in [0, 32))."""
    dx, dy = (x % 16) - 7.5, (y % 16) - 7.5
    r2 = dx * dx + dy * dy
    nx, ny = (0.06 * dx, 0.06 * dy) if r2 < 40 else (0.0, 0.0)
    nz = math.sqrt(max(0.0, 1 - nx * nx - ny * ny))
    return (0.5 + 0.5 * nx, 0.5 + 0.5 * ny, 0.5 + 0.5 * nz, 1.0)


def stripes(x, y):
    """Metallic-roughness: G roughness, B metallic; metal stripes (rough 0.25) on wood (rough 0.7)."""
    metal = (x // 8) % 2 == 0
    return (0.0, 0.25 if metal else 0.7, 1.0 if metal else 0.0, 1.0)


def holes(x, y):
    dx, dy = (x % 16) - 7.5, (y % 16) - 7.5
    return (0.2, 0.45, 0.6, 0.0 if dx * dx + dy * dy < 20 else 1.0)


def checker(x, y):
    on = ((x // 4) + (y // 4)) % 2 == 0
    return (0.8, 0.75, 0.1, 1.0) if on else (0.1, 0.25, 0.7, 1.0)


def material(name, colour=(0.8, 0.8, 0.8), metallic=0.0, roughness=0.5, specular=0.5, emission=None, strength=1.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Specular"].default_value = specular
    if emission:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
    return m


def texture_node(m, img, non_colour=False, closest=False, scale=None):
    """An Image Texture node in m (with a Mapping node when `scale` is given)."""
    nodes, links = m.node_tree.nodes, m.node_tree.links
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = img
    if non_colour:
        img.colorspace_settings.name = "Non-Color"
    if closest:
        tex.interpolation = "Closest"
    if scale:
        coords = nodes.new("ShaderNodeTexCoord")
        mapping = nodes.new("ShaderNodeMapping")
        mapping.inputs["Scale"].default_value = (scale, scale, 1)
        links.new(coords.outputs["UV"], mapping.inputs["Vector"])
        links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    return tex


def build_materials():
    m = {}
    m["Floor"] = material("Floor", roughness=0.45)
    tex = texture_node(m["Floor"], image("planks", 128, planks), scale=3)
    m["Floor"].node_tree.links.new(tex.outputs["Color"], m["Floor"].node_tree.nodes["Principled BSDF"].inputs["Base Color"])

    m["Wall"] = material("Plaster", colour=(0.75, 0.72, 0.66), roughness=0.9, specular=0.3)
    tex = texture_node(m["Wall"], image("dimples", 32, bumps), non_colour=True)
    normal = m["Wall"].node_tree.nodes.new("ShaderNodeNormalMap")
    m["Wall"].node_tree.links.new(tex.outputs["Color"], normal.inputs["Color"])
    m["Wall"].node_tree.links.new(normal.outputs["Normal"], m["Wall"].node_tree.nodes["Principled BSDF"].inputs["Normal"])

    m["Ceiling"] = material("Ceiling", colour=(0.85, 0.85, 0.85), roughness=1.0, specular=0.0)
    m["Lamp"] = material("Lamp", colour=(0, 0, 0), roughness=1.0, specular=0.0, emission=(1.0, 0.92, 0.8), strength=12.0)
    m["Gold"] = material("Gold", colour=(1.0, 0.77, 0.34), metallic=1.0, roughness=0.3)

    m["Table"] = material("Table top", colour=(0.6, 0.45, 0.3), metallic=1.0, roughness=1.0)
    tex = texture_node(m["Table"], image("stripes", 32, stripes), non_colour=True)
    split = m["Table"].node_tree.nodes.new("ShaderNodeSeparateColor")
    bsdf = m["Table"].node_tree.nodes["Principled BSDF"]
    m["Table"].node_tree.links.new(tex.outputs["Color"], split.inputs["Color"])
    m["Table"].node_tree.links.new(split.outputs["Green"], bsdf.inputs["Roughness"])
    m["Table"].node_tree.links.new(split.outputs["Blue"], bsdf.inputs["Metallic"])
    m["Legs"] = material("Legs", colour=(0.2, 0.2, 0.22), roughness=0.6)

    m["Screen"] = material("Screen", roughness=0.8)
    tex = texture_node(m["Screen"], image("holes", 64, holes))
    bsdf = m["Screen"].node_tree.nodes["Principled BSDF"]
    m["Screen"].node_tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    m["Screen"].node_tree.links.new(tex.outputs["Alpha"], bsdf.inputs["Alpha"])
    m["Screen"].blend_method = "CLIP"
    m["Screen"].alpha_threshold = 0.5

    m["Crate"] = material("Crate", roughness=0.6)
    tex = texture_node(m["Crate"], image("checker", 32, checker), closest=True)
    m["Crate"].node_tree.links.new(tex.outputs["Color"], m["Crate"].node_tree.nodes["Principled BSDF"].inputs["Base Color"])
    return m


def planar_uvs(obj, metres_per_tile=1.0):
    """UVs from each face's two in-plane world axes (box projection), one tile per metres_per_tile."""
    bpy.context.view_layer.update()  # matrix_world follows a new location only after an update
    mesh = obj.data
    layer = mesh.uv_layers.new(name="UVMap")
    for poly in mesh.polygons:
        axis = max(range(3), key=lambda a: abs(poly.normal[a]))
        u_axis, v_axis = [a for a in range(3) if a != axis]
        for li in poly.loop_indices:
            co = obj.matrix_world @ mesh.vertices[mesh.loops[li].vertex_index].co
            layer.data[li].uv = (co[u_axis] / metres_per_tile, co[v_axis] / metres_per_tile)


def build_room(m):
    floor = base.mesh_object("Floor", [(0, 0, 0), (W, 0, 0), (W, D, 0), (0, D, 0)], [(0, 1, 2, 3)], [m["Floor"]])
    planar_uvs(floor, metres_per_tile=W)  # one image over the floor; the Mapping node tiles it 3 x 3
    base.mesh_object("Ceiling", [(0, 0, H), (0, D, H), (W, D, H), (W, 0, H)], [(0, 1, 2, 3)], [m["Ceiling"]])
    outline = [(0, 0), (W, 0), (W, D), (0, D)]
    vertices, faces = [], []
    for a, b in zip(outline, outline[1:] + outline[:1]):
        n = len(vertices)
        vertices += [(*a, 0), (*a, H), (*b, H), (*b, 0)]
        faces.append((n, n + 1, n + 2, n + 3))
    walls = base.mesh_object("Walls", vertices, faces, [m["Wall"]])
    planar_uvs(walls, metres_per_tile=0.5)
    # The light: a closed fixture box under the ceiling near the back wall, its bottom face emitting.
    base.box("Lamp", (1.2, 0.6, 0.05), [m["Lamp"], m["Ceiling"]], [1, 1, 1, 1, 0, 1], location=(2.5, 3.0, H - 0.03))


def build_furniture(m):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12, radius=0.3, location=(1.0, 2.6, 0.3))
    ball = bpy.context.active_object
    ball.name = "Gold Ball"
    ball.data.materials.append(m["Gold"])
    bpy.ops.object.shade_smooth()
    top = base.box("Table Top", (1.4, 0.8, 0.05), [m["Table"]], location=(3.4, 2.9, 0.75))
    planar_uvs(top, metres_per_tile=1.4)
    for dx in (-0.6, 0.6):
        for dy in (-0.3, 0.3):
            base.box(f"Leg {dx:+.1f} {dy:+.1f}", (0.05, 0.05, 0.725), [m["Legs"]], location=(3.4 + dx, 2.9 + dy, 0.3625))
    screen = base.mesh_object("Screen", [(0.4, 3.2, 0), (1.9, 3.7, 0), (1.9, 3.7, 1.8), (0.4, 3.2, 1.8)],
                              [(0, 1, 2, 3)], [m["Screen"]])
    layer = screen.data.uv_layers.new(name="UVMap")
    for li, uv in zip(screen.data.polygons[0].loop_indices, [(0, 0), (2, 0), (2, 2.4), (0, 2.4)]):
        layer.data[li].uv = uv


def build_crate(m):
    bpy.ops.mesh.primitive_cube_add(size=0.5, location=(0, 0, 0.25))  # a cube with UVs on every face
    crate = bpy.context.active_object
    crate.name = "Crate"
    crate.data.materials.append(m["Crate"])
    for frame, location, degrees in ((0, (1.2, 1.2, 0.25), 0), (FRAME_END, (3.6, 1.4, 0.25), 60)):
        base.key(crate, "location", frame, location)
        base.key(crate, "rotation_euler", frame, (0, 0, math.radians(degrees)))


def build_scene():
    scene = base.set_up_scene(FRAME_END, RESOLUTION)
    for img in list(bpy.data.images):
        bpy.data.images.remove(img)
    m = build_materials()
    build_room(m)
    build_furniture(m)
    build_crate(m)
    base.build_camera(location=(4.7, 0.3, 1.7), target=(1.6, 3.0, 0.7), fov_y_deg=55)
    scene.frame_set(0)


if __name__ == "__main__":
    base.main(sys.argv, build_scene, textures=True, usage=__doc__)
