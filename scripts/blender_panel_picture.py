"""Takes docs/images/blender_panel.png: Blender's Render Properties with steadylight as the engine,
in a window of its own on a virtual screen (Debian's xvfb), the 3D view turned into a wide
Properties editor so that no label is cut.

    xvfb-run -a -s "-screen 0 1280x900x24" blender --factory-startup FILE.blend \\
        --addons steadylight_blender --python scripts/blender_panel_picture.py -- OUT.png

The add-on must be installed where BLENDER_USER_SCRIPTS points (tests/blender/addon_test.sh
shows how). Timers let the window draw between steps: an editor's tabs exist only once drawn.
"""
import sys

import bpy

out = sys.argv[sys.argv.index("--") + 1]


def wide_properties():
    bpy.context.scene.render.engine = "STEADYLIGHT"
    for area in bpy.context.screen.areas:
        if area.type == "VIEW_3D":
            area.type = "PROPERTIES"
    bpy.app.timers.register(render_tab, first_interval=2)


def render_tab():
    for area in bpy.context.window_manager.windows[0].screen.areas:
        if area.type == "PROPERTIES":
            area.spaces[0].context = "RENDER"
    bpy.app.timers.register(shoot, first_interval=2)


def shoot():
    window = bpy.context.window_manager.windows[0]
    area = max((a for a in window.screen.areas if a.type == "PROPERTIES"), key=lambda a: a.width)
    with bpy.context.temp_override(window=window, area=area):
        bpy.ops.screen.screenshot_area(filepath=out)
    # The panel is at the top: keep that, at a width a page shows.
    image = bpy.data.images.load(out)
    width, height = image.size
    keep = min(height, 330)
    pixels = list(image.pixels)
    cropped = bpy.data.images.new("panel", width, keep)
    cropped.pixels = pixels[(height - keep) * width * 4:]
    cropped.scale(740, round(keep * 740 / width))
    cropped.filepath_raw, cropped.file_format = out, "PNG"
    cropped.save()
    bpy.ops.wm.quit_blender()


bpy.app.timers.register(wide_properties, first_interval=2)
