"""Run inside Blender with the add-on enabled: the passes the engine registers for each method and
each choice of Passes (`--layers`) are the AOV layers steadylight writes for it, in its order, with
its channels, so that every layer lands in a pass and no pass stays empty.

    blender -b --factory-startup --addons steadylight_blender --python check_passes.py -- SCENE.json OUT
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exr_file  # noqa: E402
from steadylight_blender import engine  # noqa: E402
from steadylight_blender.program import checked_program  # noqa: E402
from steadylight_blender.properties import LAYERS  # noqa: E402

scene_file, out = sys.argv[sys.argv.index("--") + 1:]
program = checked_program("")
failures = []
choices = [layers for layers, _, _ in LAYERS]
for method in engine.PASSES:
    for layers in choices:
        folder = os.path.join(out, f"{method}_{layers}")
        subprocess.run([program, "render", scene_file, "--method", method, "--layers", layers, "--frames", "1",
                        "--size", "8x6", "--spp", "1", "--photons", "2000", "--caustic-photons", "2000",
                        "--gather-samples", "8", "--out", folder, "--blender-view-layer", "ViewLayer", "--quiet"],
                       check=True)
        name = os.path.splitext(os.path.basename(scene_file))[0]
        channels, _ = exr_file.read_exr(os.path.join(folder, f"{name}_0001.exr"))
        written = {}
        for channel in channels:
            _, pass_name, _ = channel.split(".")
            written[pass_name] = written.get(pass_name, 0) + 1
        expected = {"Combined": 4, **dict(engine.passes(method, layers))}
        if written != expected:
            failures.append(f"{method}, --layers {layers}: steadylight writes {written}, the add-on registers {expected}")
for failure in failures:
    print("FAIL", failure)
print("check_passes:", "failed" if failures else
      f"the passes of {len(engine.PASSES)} methods, each with Passes {', '.join(choices)}, match")
sys.exit(1 if failures else 0)
