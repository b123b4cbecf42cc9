"""Run by the add-on in a child Blender on a copy of the artist's file:

    blender -b --factory-startup COPY.blend --python-exit-code 1 \\
        --python scene_export_main.py -- FOLDER NAME SCENE REPORT.json

exports scene SCENE into FOLDER as NAME.glb and NAME.json (scene_export.py) and writes
REPORT.json: {"warnings": [...]} on success, {"error": "..."} and exit code 1 on failure.
"""
import json
import os
import sys
import traceback

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scene_export  # noqa: E402 (found through the path set above: this runs outside the package)


def main():
    folder, name, scene_name, report = sys.argv[sys.argv.index("--") + 1:]
    try:
        scene = bpy.data.scenes[scene_name]
        # The exporter reads the active scene; the copy keeps only this one, so that it is.
        for other in [s for s in bpy.data.scenes if s != scene]:
            bpy.data.scenes.remove(other)
        export = scene_export.export_scene(scene, folder, name)
        result = {"warnings": export.warnings}
    except Exception as error:  # the artist sees the message in Blender's report
        traceback.print_exc()
        result = {"error": f"{type(error).__name__}: {error}"}
    with open(report, "w") as f:
        json.dump(result, f)
    if "error" in result:
        sys.exit(1)


main()
