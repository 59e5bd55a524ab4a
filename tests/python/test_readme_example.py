"""README.md's Python example ("## Python"), run as written in the folder simulated_clip.py fills
(`clip/` from `reftrack simulate`, `map/` from `reftrack prepare`, the README's two commands)."""

import os
import pathlib
import re
import subprocess
import sys
import unittest

import simulated_clip

README = pathlib.Path(os.environ["REFTRACK_README"])


def example():
    text = README.read_text()
    section = text[text.index("\n## Python\n"):]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


class ReadmeExample(unittest.TestCase):
    def test_runs_and_tracks_every_frame_within_5_mm(self):
        simulated_clip.make()
        code = example()
        self.assertLessEqual(len(code.strip().splitlines()), 20)
        out = subprocess.run([sys.executable, "-c", code], cwd=simulated_clip.WORK, check=True,
                             capture_output=True, text=True).stdout
        errors = [float(mm) for mm in re.findall(r"([0-9.]+) mm from the truth", out)]
        self.assertGreaterEqual(len(errors), simulated_clip.FRAMES - 2, out)
        self.assertLess(max(errors), 5.0, out)


if __name__ == "__main__":
    unittest.main(verbosity=2)
