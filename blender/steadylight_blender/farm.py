"""Render > Submit to Slurm: the scene exported as a render would export it, then `steadylight submit`
(docs/farm.md) for the frame range, in the folder a render would use, so that the farm's frames
and a later render from Blender share the static cache and the frames already written."""
import os
import subprocess
import tempfile

import bpy

from . import job as jobs
from .program import ProgramError
from .render_run import frame_list


class STEADYLIGHT_OT_submit(bpy.types.Operator):
    bl_idname = "steadylight.submit"
    bl_label = "Submit to Slurm"
    bl_description = "Export the scene and render its frames on a Slurm cluster with `steadylight submit`"

    dry_run: bpy.props.BoolProperty(name="Dry Run", default=False,
                                    description="Write the job scripts and show the sbatch lines; submit nothing")

    def execute(self, context):
        scene = context.scene
        handle, copy = tempfile.mkstemp(prefix="steadylight_", suffix=".blend")
        os.close(handle)
        try:
            program = jobs.program_from_preferences(context)
            jobs.copy_blend(copy)
            job = jobs.Job(scene, context.view_layer.name, program, copy)
        except ProgramError as error:
            self.report({"ERROR"}, f"steadylight: {error}")
            return {"CANCELLED"}
        finally:
            os.remove(copy)
        for warning in job.warnings:
            self.report({"WARNING"}, f"steadylight: {warning}")
        command = [program, "submit", job.scene_file, "--out", job.folder, "--frames", frame_list(job.frames),
                   "--chunk", str(scene.steadylight.chunk_frames)] + job.options + (["--dry-run"] if self.dry_run else [])
        out = subprocess.run(command, capture_output=True, text=True, errors="replace")
        with open(os.path.join(job.folder, "steadylight_blender.log"), "a") as log:
            log.write("$ " + " ".join(command) + "\n" + out.stdout + out.stderr)
        if out.returncode != 0:
            self.report({"ERROR"}, f"steadylight submit failed: {(out.stderr or out.stdout).strip()}")
            return {"CANCELLED"}
        lines = [line for line in out.stdout.splitlines() if line.startswith(("submitted jobs", "would run"))]
        for line in lines:
            self.report({"INFO"}, f"steadylight: {line}")
        self.report({"INFO"}, f"steadylight: frames go to {job.folder}")
        return {"FINISHED"}


def register():
    bpy.utils.register_class(STEADYLIGHT_OT_submit)


def unregister():
    bpy.utils.unregister_class(STEADYLIGHT_OT_submit)
