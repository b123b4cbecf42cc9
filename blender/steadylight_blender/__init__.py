"""steadylight for Blender: a render engine that exports the scene with Blender's glTF exporter and
renders it with the steadylight program (docs/blender.md)."""

bl_info = {
    "name": "steadylight",
    "author": "the steadylight developers",
    "version": (0, 2, 0),
    "blender": (3, 4, 0),
    "location": "Render Properties > Render Engine > steadylight",
    "description": "Global illumination for animations: photon mapping whose frames cost what moves",
    "category": "Render",
}

from . import engine, farm, preferences, properties, ui  # noqa: E402 (after bl_info, as Blender reads it)

MODULES = (properties, preferences, engine, farm, ui)


def register():
    for module in MODULES:
        module.register()


def unregister():
    for module in reversed(MODULES):
        module.unregister()
