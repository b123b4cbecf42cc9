"""Where the steadylight program is (Preferences > Add-ons > steadylight)."""
import bpy

from .program import ProgramError, checked_program


class SteadylightPreferences(bpy.types.AddonPreferences):
    # The add-on's module: `steadylight_blender`, or `bl_ext.<repository>.steadylight_blender`
    # where Blender 4.2+ installs it as an extension.
    bl_idname = __package__

    program: bpy.props.StringProperty(name="steadylight Program", subtype="FILE_PATH", default="",
                                      description="The steadylight executable; empty: found on PATH")

    def draw(self, context):
        self.layout.prop(self, "program")
        try:
            self.layout.label(text=f"Found: {checked_program(self.program)}", icon="CHECKMARK")
        except ProgramError as error:
            self.layout.label(text=str(error), icon="ERROR")


def register():
    bpy.utils.register_class(SteadylightPreferences)


def unregister():
    bpy.utils.unregister_class(SteadylightPreferences)
