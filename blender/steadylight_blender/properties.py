"""The render settings the add-on keeps in the .blend (Render Properties > steadylight)."""
import bpy

METHODS = [
    ("localized", "Localized", "The paper's method: the static light once per segment, each frame only what moves"),
    ("photon", "Photon mapping", "Photon mapping with final gathering, every frame from scratch"),
    ("frozen", "Frozen", "The static cache reused as it is (for comparison)"),
    ("path", "Path tracing", "Path-traced ground truth (slow)"),
]

# steadylight's --layers: which AOV layers it computes and writes, each a pass (engine.py).
LAYERS = [
    ("all", "All", "The terms of the light and the method's analysis layers (its records, influence, estimates)"),
    ("terms", "Light Terms", "Direct, indirect, caustic and specular light only: a production render, "
                             "faster and with smaller files"),
    ("beauty", "Combined Only", "No passes beyond Combined"),
]


class SteadylightSettings(bpy.types.PropertyGroup):
    method: bpy.props.EnumProperty(name="Method", items=METHODS, default="localized")
    layers: bpy.props.EnumProperty(name="Passes", items=LAYERS, default="all")
    samples: bpy.props.IntProperty(
        name="Samples", default=0, min=0, max=1048576,
        description="Camera rays per pixel; 0: the method's default (16, or 64 for path tracing)")
    photons: bpy.props.IntProperty(name="Photons", default=200000, min=0, max=2**31 - 1,
                                   description="Photon paths emitted per frame for the global map")
    cache_accuracy: bpy.props.FloatProperty(
        name="Cache Accuracy", default=0.25, min=0.01, max=2,
        description="Ward's a: smaller places more irradiance records")
    chunk_frames: bpy.props.IntProperty(name="Frames per Farm Job", default=10, min=1,
                                        description="Frames each Slurm array task renders")


def register():
    bpy.utils.register_class(SteadylightSettings)
    bpy.types.Scene.steadylight = bpy.props.PointerProperty(type=SteadylightSettings)


def unregister():
    del bpy.types.Scene.steadylight
    bpy.utils.unregister_class(SteadylightSettings)
