"""The steadylight panel in Render Properties, shown when steadylight is the render engine."""
import bpy


class RENDER_PT_steadylight(bpy.types.Panel):
    bl_label = "steadylight"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {"STEADYLIGHT"}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES

    def draw(self, context):
        settings = context.scene.steadylight
        layout = self.layout
        layout.use_property_split = True
        layout.prop(settings, "method")
        if settings.method != "path":
            layout.prop(settings, "layers")
        layout.prop(settings, "samples")
        if settings.method != "path":
            layout.prop(settings, "photons")
        if settings.method in ("localized", "frozen"):
            layout.prop(settings, "cache_accuracy")
        layout.prop(context.scene.render, "film_transparent", text="Transparent Background")
        layout.separator()
        layout.prop(settings, "chunk_frames")
        layout.operator("steadylight.submit", icon="NETWORK_DRIVE")


def register():
    bpy.utils.register_class(RENDER_PT_steadylight)


def unregister():
    bpy.utils.unregister_class(RENDER_PT_steadylight)
