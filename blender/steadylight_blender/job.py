"""A render job: the scene exported once, its folder, and the steadylight run behind the frames.

Blender makes a new engine for every frame of an animation, so the job lives here, at module
level: made by the first frame after `render_init`, ended by `render_complete` or
`render_cancel` (engine.py registers the handlers).

The folder rule (docs/blender.md, "Where the frames go"): beside a saved file,
`<file>_steadylight/<scene>_<key>/`; for an unsaved file, the same under Blender's temporary
folder. The key is a hash of the exported scene's files and of the settings, so a changed scene
or setting gets a new folder and an unchanged one resumes where an earlier run stopped (the
static cache and the frames already written are reused).
"""
import hashlib
import json
import os
import re
import shutil
import subprocess
import tempfile

import bpy

from .program import ProgramError, checked_program
from .render_run import RenderRun

EXPORT_SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "scene_export_main.py")


class Job:
    def __init__(self, scene, view_layer, program, copy_path):
        self.scene_name = safe_name(scene.name)
        self.view_layer = view_layer
        self.settings = scene.steadylight
        self.frames = list(range(scene.frame_start, scene.frame_end + 1, max(1, scene.frame_step)))
        base = output_base(scene)
        os.makedirs(base, exist_ok=True)
        staging = tempfile.mkdtemp(prefix=".export-", dir=base)
        try:
            self.warnings = export_copy(copy_path, scene.name, staging, self.scene_name)
            self.options = render_options(scene, view_layer)
            key = folder_key(staging, self.options)
            self.folder = os.path.join(base, f"{self.scene_name}_{key}")
            if not os.path.isdir(self.folder):
                os.rename(staging, self.folder)
        finally:
            shutil.rmtree(staging, ignore_errors=True)
        self.program = program
        self.run = None

    @property
    def scene_file(self):
        return os.path.join(self.folder, self.scene_name + ".json")

    def start(self, first_frame, whole_range):
        """Starts rendering at `first_frame`: to the end of the range for an animation, else that frame."""
        frames = [f for f in self.frames if f >= first_frame] if whole_range else [first_frame]
        if first_frame not in frames:
            frames = [first_frame]
        self.run = RenderRun(self.program, self.scene_file, self.folder, self.scene_name, frames, self.options)

    def covers(self, frame):
        return self.run is not None and frame in self.run.frames and (
            self.run.running() or os.path.exists(self.run.manifest(frame)))

    def stop(self):
        if self.run is not None:
            self.run.stop()


def safe_name(name):
    """A scene name as steadylight accepts it in file names (letters, digits, - and _)."""
    return re.sub(r"[^A-Za-z0-9_-]+", "_", name).strip("_") or "scene"


def output_base(scene):
    if bpy.data.filepath:
        folder, file_name = os.path.split(bpy.path.abspath(bpy.data.filepath))
        return os.path.join(folder, os.path.splitext(file_name)[0] + "_steadylight")
    temporary = bpy.context.preferences.filepaths.temporary_directory or tempfile.gettempdir()
    return os.path.join(temporary, "steadylight")


def copy_blend(path):
    """The artist's data as it is now, saved edits or not, into a .blend a child Blender can open.
    Called from the engine's update(), which Blender runs holding its render lock; writing a
    library touches no operator, handler or window (docs/blender.md, "Exporting")."""
    bpy.data.libraries.write(path, set(bpy.data.scenes), path_remap="ABSOLUTE", fake_user=True)


def export_copy(copy_path, scene_name, folder, name):
    """Exports the copy's scene `scene_name` in a child Blender; returns the export's warnings."""
    report = os.path.join(folder, "export_report.json")
    command = [bpy.app.binary_path, "-b", "--factory-startup", copy_path, "--python-exit-code", "1",
               "--python", EXPORT_SCRIPT, "--", folder, name, scene_name, report]
    out = subprocess.run(command, capture_output=True, text=True, errors="replace")
    try:
        with open(report) as f:
            result = json.load(f)
        os.remove(report)
    except (OSError, ValueError):
        result = {"error": f"the export stopped (exit code {out.returncode}):\n" + out.stdout[-2000:] + out.stderr[-2000:]}
    if "error" in result:
        raise ProgramError("export: " + result["error"])
    return result["warnings"]


def render_options(scene, view_layer):
    s = scene.steadylight
    # The engine registers a pass for each layer these write (engine.passes).
    options = ["--method", s.method, "--exr-type", "float", "--layers", s.layers, "--blender-view-layer", view_layer,
               "--photons", str(s.photons), "--cache-accuracy", f"{s.cache_accuracy:g}"]
    if s.samples > 0:
        options += ["--spp", str(s.samples)]
    if scene.render.film_transparent:
        options.append("--transparent-background")
    return options


def folder_key(folder, options):
    """16 hex digits of a hash of every file in `folder` and of `options`."""
    digest = hashlib.sha256("\0".join(options).encode())
    for name in sorted(os.listdir(folder)):
        digest.update(name.encode() + b"\0")
        with open(os.path.join(folder, name), "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                digest.update(block)
    return digest.hexdigest()[:16]


def program_from_preferences(context):
    addon = context.preferences.addons.get(__package__)
    setting = addon.preferences.program if addon is not None else ""
    return checked_program(setting)
