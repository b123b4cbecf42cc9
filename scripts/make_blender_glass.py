"""Builds the truth suite's glass fixture in Blender itself and exports it with Blender's own glTF
exporter: rough glass (KHR_materials_transmission with a roughness) and absorbing glass
(KHR_materials_volume), docs/truth-suite.md "Glass: absorption and roughness".

Run headless:  blender -b --factory-startup --python scripts/make_blender_glass.py -- OUT.glb [--blend OUT.blend]

A 4 m x 3 m room, 2.5 m high (Blender's Z-up metres), every opaque surface a Principled BSDF
with Roughness 1 and Specular 0 (Lambert with a grazing-angle coat, as in scripts/make_blender_scene.py),
lit by an emissive panel under the ceiling, with three glass objects:
- an amber ball (smooth glass, IOR 1.5) that absorbs: a Volume Absorption node (Color
  (0.9, 0.55, 0.2), Density 4, so attenuationDistance 0.25 m) on the Material Output's Volume,
  and the exporter's "glTF Material Output" group with Thickness 0.6 (its diameter), which the
  exporter needs before it writes KHR_materials_volume. It slides 0.4 m over frames 0-12;
- a frosted pane (Roughness 0.3, no volume: thin-walled) in front of coloured stripes on the
  back wall, which it blurs;
- a blue block that is both: Roughness 0.15 and a volume (Color (0.35, 0.55, 0.95), Density 5).
A camera looks at them from the front wall, fov_y 60 degrees (the exporter writes the aspect
ratio, 4:3, and not the size: steadylight makes it 320 x 240).

It reuses scripts/make_blender_scene.py's helpers (set_up_scene, principled, mesh_object, box,
walls, smooth_sphere, key, build_camera, export_glb, main).
"""
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_blender_scene as base  # noqa: E402  (Blender's --python puts nothing on sys.path)

FRAME_END = 12
RESOLUTION = (160, 120)
W, D, H = 4.0, 3.0, 2.5


def gltf_output_group():
    """The exporter's "glTF Material Output" node group: its Thickness input says the mesh is a
    volume (the exporter writes KHR_materials_volume only when it is above 0)."""
    group = bpy.data.node_groups.get("glTF Material Output")
    if group is None:
        group = bpy.data.node_groups.new("glTF Material Output", "ShaderNodeTree")
        group.inputs.new("NodeSocketFloat", "Occlusion")
        group.inputs.new("NodeSocketFloat", "Thickness").default_value = 0.0
        group.nodes.new("NodeGroupInput")
        group.nodes.new("NodeGroupOutput")
    return group


def glass(name, roughness, colour=None, density=0.0, thickness=0.0):
    """A Principled BSDF with Transmission 1 and IOR 1.5; with `colour` a Volume Absorption node
    on the output's Volume and the glTF output group's Thickness set."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    m.use_backface_culling = True  # doubleSided false: glTF wants no volume on double-sided materials
    nodes, links = m.node_tree.nodes, m.node_tree.links
    bsdf = nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    bsdf.inputs["Transmission"].default_value = 1.0
    bsdf.inputs["IOR"].default_value = 1.5
    bsdf.inputs["Roughness"].default_value = roughness
    if colour:
        absorption = nodes.new("ShaderNodeVolumeAbsorption")
        absorption.inputs["Color"].default_value = (*colour, 1.0)
        absorption.inputs["Density"].default_value = density
        links.new(absorption.outputs["Volume"], nodes["Material Output"].inputs["Volume"])
        settings = nodes.new("ShaderNodeGroup")
        settings.node_tree = gltf_output_group()
        settings.inputs["Thickness"].default_value = thickness
    return m


def build_room(mat):
    base.mesh_object("Floor", [(0, 0, 0), (W, 0, 0), (W, D, 0), (0, D, 0)], [(0, 1, 2, 3)], [mat["Floor"]])
    base.mesh_object("Ceiling", [(0, 0, H), (0, D, H), (W, D, H), (W, 0, H)], [(0, 1, 2, 3)], [mat["Wall"]])
    base.walls("Walls", [(0, 0), (W, 0), (W, D), (0, D)], H, [mat["Wall"]])
    # Stripes on the back wall behind the frosted pane, 1 cm proud of it.
    for i, colour in enumerate(("Red", "Green", "Blue", "Red", "Green")):
        base.box(f"Stripe {i}", (0.12, 0.02, 1.6), [mat[colour]], location=(1.9 + 0.24 * i, D - 0.01, 0.9))
    # The light: a closed fixture under the ceiling, its bottom face emitting.
    base.box("Lamp", (1.2, 0.8, 0.05), [mat["Lamp"], mat["Wall"]], [1, 1, 1, 1, 0, 1], location=(2.0, 1.2, H - 0.03))


CONTACT_GAP = 0.001  # metres between the blue block and the floor


def build_glass(mat):
    ball = base.smooth_sphere("Amber Ball", 0.3, (1.3, 1.5, 0.3), mat["Amber"], segments=48, rings=24)
    for frame, x in ((0, 1.3), (FRAME_END, 1.7)):
        base.key(ball, "location", frame, (x, 1.5, 0.3))
    base.box("Frosted Pane", (1.3, 0.03, 1.1), [mat["Frosted"]], location=(2.35, 2.4, 0.75))
    # 1 mm above the floor: glass standing exactly on it meets it in a plane, where a ray finds
    # the glass's bottom and the floor at one distance and either may come first (the path
    # tracer lost a quarter of the block's blue that way; docs/notes/truth-glass-on-floor.md).
    base.box("Blue Block", (0.35, 0.35, 0.35), [mat["Blue Glass"]], location=(2.8, 1.2, 0.175 + CONTACT_GAP))


def build_scene():
    scene = base.set_up_scene(FRAME_END, RESOLUTION)
    mat = {name: base.principled(name, colour) for name, colour in (
        ("Floor", (0.7, 0.7, 0.7)), ("Wall", (0.75, 0.74, 0.70)),
        ("Red", (0.75, 0.1, 0.08)), ("Green", (0.1, 0.6, 0.15)), ("Blue", (0.1, 0.2, 0.75)))}
    mat["Lamp"] = base.principled("Lamp", (0, 0, 0), emission=(1.0, 0.95, 0.85), strength=10.0)
    mat["Amber"] = glass("Amber", 0.0, colour=(0.9, 0.55, 0.2), density=4.0, thickness=0.6)
    mat["Frosted"] = glass("Frosted", 0.3)
    mat["Blue Glass"] = glass("Blue Glass", 0.15, colour=(0.35, 0.55, 0.95), density=5.0, thickness=0.35)
    build_room(mat)
    build_glass(mat)
    base.build_camera(location=(2.1, 0.1, 1.4), target=(2.1, 1.9, 0.45), fov_y_deg=60)
    scene.frame_set(0)


if __name__ == "__main__":
    base.main(sys.argv, build_scene, usage=__doc__)
