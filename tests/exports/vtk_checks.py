"""What the checks of sphclip's exports with VTK's own readers share: VTK's
Python module (exit 77, ctest's "skipped", without it), the command line
(PATH/TO/sphclip SOURCE_DIR), a short run of a shipped scene, and the list
of failed checks that decides the exit status."""
import os
import subprocess
import sys

try:
    import vtk  # noqa: F401 (the checks use it as vtk_checks.vtk)
except ImportError:
    print("skipped: VTK's Python module is not installed (apt-get install python3-vtk9)")
    sys.exit(77)

exe, source = sys.argv[1], sys.argv[2]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAILED:", what)


def run(scene, out, args, duration="0.04", **options):
    """sphclip run of scenes/SCENE into OUT, 1 thread, no pictures, frames
    every 0.02 s for DURATION s, with ARGS added; OPTIONS go to subprocess.run."""
    command = [exe, "run", os.path.join(source, "scenes", scene), "--out", out, "--quiet",
               "--no-png", "--no-mp4", "--threads", "1", "--duration", duration, "--fps", "50"]
    return subprocess.run(command + args, env=dict(os.environ, OMP_WAIT_POLICY="passive"),
                          **options)


def finish(passed):
    """Exits 1 naming the count of failed checks, else prints PASSED."""
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print(passed)
