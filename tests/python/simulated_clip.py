"""The clip the Python tests track: 20 simulated hand-held frames at 640x480 (`reftrack simulate`)
and the map `reftrack prepare` makes from its two reference images, in REFTRACK_TEST_WORK; made
once per process (about 12 s on 2 cores). REFTRACK_BINARY: the `reftrack` command."""

import os
import pathlib
import shutil
import subprocess

BINARY = os.environ["REFTRACK_BINARY"]
WORK = pathlib.Path(os.environ["REFTRACK_TEST_WORK"])
CLIP, MAP = WORK / "clip", WORK / "map"
FRAMES = 20
_made = False


def make():
    global _made
    if _made:
        return
    shutil.rmtree(WORK, ignore_errors=True)
    WORK.mkdir(parents=True)

    def run(*args):
        subprocess.run([BINARY, *args], check=True, capture_output=True)

    run("simulate", "--preset", "handheld", "--frames", str(FRAMES), "--out", str(CLIP))
    run("prepare", "--camera", str(CLIP / "camera.yml"), "--ref", str(CLIP / "reference_a.png"),
        "--ref", str(CLIP / "reference_b.png"), "--marker", "DICT_6X6_250:23:0.2",
        "--out", str(MAP))
    _made = True
