"""steadylight as a Blender render engine (docs/blender.md).

Per frame Blender calls update() then render() on a new engine. The first frame of a render
copies the artist's data (update(), under Blender's render lock), exports it in a child Blender,
and starts one `steadylight render` for the rest of the range (job.py); each frame then waits
for its files and loads them into the render result: the beauty as Combined and every AOV
layer as a pass of the same name, registered in update_render_passes() so that the compositor
and the image editor list them. Esc (test_break) stops the run with SIGINT; the next render in
the same folder resumes it.
"""
import os
import tempfile

import bpy
from bpy.app.handlers import persistent

from . import job as jobs
from .program import ProgramError
from .render_run import RunFailed
from .scene_export import resolution

# The AOV layers of each method, in the order steadylight writes them, and their channels
# (methods/method.cpp; tests/blender/check_passes.py checks them against steadylight's EXRs).
LOCALIZED_PASSES = [("direct", 3), ("indirect", 3), ("caustic", 3), ("specular", 3), ("indirect_static", 3),
                    ("L_y", 3), ("L_t", 3), ("influence", 1), ("dynamic", 1), ("static_records", 1),
                    ("dynamic_records", 1), ("changed", 1)]
PASSES = {
    "localized": LOCALIZED_PASSES,
    "frozen": LOCALIZED_PASSES,
    "photon": [("direct", 3), ("indirect", 3), ("caustic", 3), ("specular", 3), ("records", 1)],
    "path": [],
}
# The four terms of the light, which sum to Combined; a method's other layers are its analysis
# layers, which `--layers terms` leaves out (properties.py LAYERS).
TERMS = ("direct", "indirect", "caustic", "specular")


def passes(method, layers):
    """The passes beyond Combined of `method`'s frames rendered with `--layers layers`."""
    if layers == "beauty":
        return []
    return [(name, channels) for name, channels in PASSES[method] if layers == "all" or name in TERMS]


# The render's job (job.py), shared by the engines Blender makes for its frames.
current = {"job": None, "copy": None, "error": None}


def end_job():
    if current["job"] is not None:
        current["job"].stop()
    if current["copy"] is not None and os.path.exists(current["copy"]):
        os.remove(current["copy"])
    current.update(job=None, copy=None, error=None)


@persistent
def on_render_init(_scene, _depsgraph=None):
    end_job()


@persistent
def on_render_end(_scene, _depsgraph=None):
    end_job()


def test_break_after_frames():
    """STEADYLIGHT_ADDON_TEST_BREAK_AFTER=N (tests only): a break once N frames are written."""
    value = os.environ.get("STEADYLIGHT_ADDON_TEST_BREAK_AFTER")
    return int(value) if value else None


class SteadylightRenderEngine(bpy.types.RenderEngine):
    bl_idname = "STEADYLIGHT"
    bl_label = "steadylight"
    bl_use_preview = False
    bl_use_postprocess = True
    # The viewport's Material Preview and Rendered modes show Eevee's picture of the scene:
    # steadylight renders frames, not an interactive view (docs/blender.md).
    bl_use_eevee_viewport = True

    def update(self, data, depsgraph):
        if current["job"] is None and current["copy"] is None:
            handle, path = tempfile.mkstemp(prefix="steadylight_", suffix=".blend")
            os.close(handle)
            jobs.copy_blend(path)
            current["copy"] = path

    def update_render_passes(self, scene=None, renderlayer=None):
        self.register_pass(scene, renderlayer, "Combined", 4, "RGBA", "COLOR")
        for name, channels in passes(scene.steadylight.method, scene.steadylight.layers):
            if channels == 3:
                self.register_pass(scene, renderlayer, name, 3, "RGB", "COLOR")
            else:
                self.register_pass(scene, renderlayer, name, 1, "X", "VALUE")

    def render(self, depsgraph):
        scene = depsgraph.scene
        frame = scene.frame_current
        try:
            job = self.job_for(scene, depsgraph.view_layer.name)
            if depsgraph.view_layer.name != job.view_layer:
                return  # the export warned: one view layer is rendered
            if not job.covers(frame):
                job.stop()
                job.start(frame, whole_range=self.is_animation)
            if not job.run.wait_for(frame, self.should_stop, self.show_progress):
                self.report({"INFO"}, f"steadylight: stopped; the next render resumes in {job.folder}")
                return
            result = self.begin_result(0, 0, *resolution(scene))
            try:
                result.load_from_file(job.run.exr(frame))
            finally:
                self.end_result(result)
        except (ProgramError, RunFailed, OSError) as error:
            current["error"] = str(error)
            self.report({"ERROR"}, f"steadylight: {error}")

    def job_for(self, scene, view_layer):
        if current["error"] is not None:
            raise ProgramError(current["error"])
        if current["job"] is None:
            self.update_stats("steadylight", "exporting the scene")
            program = jobs.program_from_preferences(bpy.context)
            current["job"] = jobs.Job(scene, view_layer, program, current["copy"])
            for warning in current["job"].warnings:
                self.report({"WARNING"}, f"steadylight: {warning}")
        return current["job"]

    def should_stop(self):
        limit = test_break_after_frames()
        if limit is not None and current["job"].run.frames_done() >= limit:
            # Blender stops an animation on Esc by itself; a test's break stops it by an error.
            self.report({"ERROR"}, "steadylight: stopped by STEADYLIGHT_ADDON_TEST_BREAK_AFTER")
            return True
        return self.test_break()

    def show_progress(self, run):
        self.update_progress(run.frames_done() / len(run.frames))
        # The phase is the log line's first part ("frame 12  0.53 s", "static cache: ..."); the
        # stats line changes only with it (in the background Blender prints every change).
        stats = f"{run.frames_done()}/{len(run.frames)} frames | {run.phase().split('|')[0].strip()[:72]}"
        if stats != current.get("stats"):
            current["stats"] = stats
            self.update_stats("steadylight", stats)


HANDLERS = ((bpy.app.handlers.render_init, on_render_init), (bpy.app.handlers.render_complete, on_render_end),
            (bpy.app.handlers.render_cancel, on_render_end))


def register():
    bpy.utils.register_class(SteadylightRenderEngine)
    for handlers, handler in HANDLERS:
        handlers.append(handler)


def unregister():
    for handlers, handler in HANDLERS:
        if handler in handlers:
            handlers.remove(handler)
    end_job()
    bpy.utils.unregister_class(SteadylightRenderEngine)
