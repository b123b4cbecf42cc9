"""One `steadylight render` of an exported scene, running beside Blender (no bpy: tested alone).

Blender asks for one frame at a time; the run renders the whole range in one process, so that
the segment's static cache is computed once, and hands each frame back when its manifest
(written last, after the frame's files) appears. Stopping sends SIGINT: steadylight finishes
nothing half-way, and the next run in the folder resumes at the first frame not complete.
"""
import os
import signal
import subprocess
import threading
import time
from collections import deque


class RunFailed(Exception):
    """steadylight stopped with an error: the message ends with its last log lines."""


class RenderRun:
    def __init__(self, program, scene_file, out_dir, scene_name, frames, options):
        """Starts `program render scene_file --frames <frames> --out out_dir <options>`."""
        self.out_dir, self.scene_name, self.frames = out_dir, scene_name, list(frames)
        self.lines = deque(maxlen=20)
        self.log_path = os.path.join(out_dir, "steadylight_blender.log")
        command = [program, "render", scene_file, "--out", out_dir, "--no-progress",
                   "--frames", frame_list(self.frames)] + options
        self._log = open(self.log_path, "a")
        self._log.write("$ " + " ".join(command) + "\n")
        self._log.flush()
        self.process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                        errors="replace")
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self):
        for line in self.process.stdout:
            self._log.write(line)
            self._log.flush()
            self.lines.append(line.rstrip("\n"))

    def phase(self):
        """The last log line without its time stamp and level: what steadylight is doing."""
        line = self.lines[-1] if self.lines else "starting"
        return line.split("] ", 2)[-1] if line.startswith("[") else line

    def manifest(self, frame):
        return os.path.join(self.out_dir, f"{self.scene_name}_{frame:04d}.manifest.json")

    def exr(self, frame):
        return os.path.join(self.out_dir, f"{self.scene_name}_{frame:04d}.exr")

    def frames_done(self):
        return sum(os.path.exists(self.manifest(f)) for f in self.frames)

    def wait_for(self, frame, should_stop, on_progress, poll_s=0.1):
        """Waits until `frame` is written (True), or `should_stop()` (False, the run stopped). Raises
        RunFailed when steadylight ends without writing it."""
        while not os.path.exists(self.manifest(frame)):
            if should_stop():
                self.stop()
                return False
            if self.process.poll() is not None:
                self._reader.join(timeout=5)
                if os.path.exists(self.manifest(frame)):
                    break
                tail = "\n".join(self.lines)
                raise RunFailed(f"steadylight stopped (exit code {self.process.returncode}) before frame {frame}; "
                                f"its log is {self.log_path}:\n{tail}")
            on_progress(self)
            time.sleep(poll_s)
        on_progress(self)
        return True

    def running(self):
        return self.process.poll() is None

    def stop(self, timeout_s=60):
        """SIGINT (steadylight stops within about a second, leaving finished frames), then SIGKILL."""
        if self.running():
            self.process.send_signal(signal.SIGINT)
            try:
                self.process.wait(timeout=timeout_s)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self._reader.join(timeout=5)
        self._log.close()


def frame_list(frames):
    """Frames as steadylight's --frames: A-B:S when evenly spaced, else a comma list."""
    if len(frames) == 1:
        return str(frames[0])
    step = frames[1] - frames[0]
    if step > 0 and all(b - a == step for a, b in zip(frames, frames[1:])):
        return f"{frames[0]}-{frames[-1]}" + (f":{step}" if step != 1 else "")
    return ",".join(map(str, frames))
