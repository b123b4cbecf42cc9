"""Finding the steadylight program and checking that it is recent enough (no bpy: tested alone)."""
import os
import re
import shutil
import subprocess

# The daylight release: suns, worlds and portals, which the export writes, and
# --blender-view-layer, which the frames are read back by.
REQUIRED_VERSION = (0, 2, 0)


class ProgramError(Exception):
    """A message for Blender's report: what is wrong with the program and what to do."""


def find_program(setting):
    """The program the preferences name, or `steadylight` on PATH when they name none."""
    if setting:
        path = os.path.abspath(os.path.expanduser(setting))
        if not os.path.isfile(path) or not os.access(path, os.X_OK):
            raise ProgramError(f"steadylight program {path} does not exist or cannot be run: set its path in "
                               "Preferences > Add-ons > steadylight")
        return path
    path = shutil.which("steadylight")
    if path is None:
        raise ProgramError("steadylight is not on PATH: install it (README, 'Two commands') or set the program's "
                           "path in Preferences > Add-ons > steadylight")
    return path


def program_version(path):
    """The version `steadylight --version` prints, as a tuple of three numbers."""
    try:
        out = subprocess.run([path, "--version"], capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.TimeoutExpired) as error:
        raise ProgramError(f"{path} --version failed: {error}")
    match = re.match(r"steadylight (\d+)\.(\d+)\.(\d+)", out.stdout.strip())
    if out.returncode != 0 or match is None:
        raise ProgramError(f"{path} does not look like steadylight: `--version` printed {out.stdout.strip()!r}")
    return tuple(int(n) for n in match.groups())


def checked_program(setting):
    """The program's path, if it is there and at least REQUIRED_VERSION; else ProgramError."""
    path = find_program(setting)
    version = program_version(path)
    if version < REQUIRED_VERSION:
        raise ProgramError(f"{path} is steadylight {'.'.join(map(str, version))}; this add-on needs "
                           f"{'.'.join(map(str, REQUIRED_VERSION))} or later")
    return path
