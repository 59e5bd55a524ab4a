"""The Python module `reftrack` (python/), run by CTest with Debian's python3 on the build tree.

The poses tracked from Python on a simulated clip (simulated_clip.py) are checked against the
simulator's ground truth, bad input against the exceptions it must raise, and the poses of the
same frames tracked with the machine busy against those of a quiet run (the binding's time per
frame is a benchmark: scripts/bench-python-binding.sh).
"""

import ast
import os
import pathlib
import subprocess
import sys
import unittest

import cv2
import numpy as np
import reftrack
import simulated_clip
from simulated_clip import BINARY, CLIP, FRAMES, MAP, WORK


def setUpModule():
    simulated_clip.make()


def frames():
    return [cv2.imread(str(p)) for p in sorted((CLIP / "frames").glob("*.png"))]


def true_centres():
    # TUM lines: timestamp, camera centre in the world (tx ty tz), orientation quaternion.
    return np.loadtxt(CLIP / "groundtruth.txt")[:, 1:4]


def centre(world_to_camera):
    return -world_to_camera[:3, :3].T @ world_to_camera[:3, 3]


class TrackerFromPython(unittest.TestCase):
    def test_version_is_the_command_lines(self):
        out = subprocess.run([BINARY, "--version"], check=True, capture_output=True, text=True)
        self.assertEqual(out.stdout.strip(), "reftrack " + reftrack.__version__)

    def test_type_stubs_declare_what_the_module_has(self):
        # reftrack.pyi lies beside the module, in the build tree as after an install.
        stub = ast.parse((pathlib.Path(reftrack.__file__).parent / "reftrack.pyi").read_text())
        classes = {node.name: node for node in stub.body if isinstance(node, ast.ClassDef)}
        self.assertEqual(set(classes), {"Error", "Result", "Tracker"})
        for name, node in classes.items():
            declared = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
            actual = {m for m in vars(getattr(reftrack, name)) if not m.startswith("_")}
            self.assertEqual(declared, actual, name)

    def test_camera_centres_lie_within_5_mm_of_the_truth(self):
        tracker = reftrack.Tracker.open_map(MAP)
        self.assertEqual(tracker.mode, "6dof")
        self.assertEqual(tracker.image_size, (640, 480))
        self.assertEqual(tracker.camera_matrix.shape, (3, 3))
        truth = true_centres()
        self.assertEqual(len(truth), FRAMES)
        errors = []
        for k, frame in enumerate(frames()):
            r = tracker.track(frame)
            self.assertEqual(r.frame_index, k)
            self.assertIn(r.state, ("initialising", "tracking", "lost"))
            if r.state != "tracking":
                self.assertIsNone(r.world_to_camera)
                self.assertIsNone(r.predicted_error_px)
                self.assertTrue(r.reason)
                continue
            T = r.world_to_camera
            self.assertEqual((T.shape, T.dtype), ((4, 4), np.float64))
            np.testing.assert_allclose(T[3], [0, 0, 0, 1])
            self.assertEqual(r.covariance.shape, (6, 6))
            self.assertIsNone(r.homography)
            self.assertGreater(r.inliers, 0)
            self.assertGreaterEqual(min(r.reference_a, r.reference_b), 0)
            self.assertIsInstance(r.relocalised, bool)
            self.assertGreater(r.milliseconds, 0.0)
            errors.append(1000 * np.linalg.norm(centre(T) - truth[k]))
        print(f"tracked {len(errors)} of {FRAMES} frames; camera centre error mean "
              f"{np.mean(errors):.2f} mm, max {np.max(errors):.2f} mm")
        self.assertGreaterEqual(len(errors), FRAMES - 2)
        self.assertLess(max(errors), 5.0)

    def test_grey_frames_strided_views_and_copies_track_alike(self):
        clip = frames()[:6]
        runs = {}
        tracker = reftrack.Tracker.open_map(MAP)
        for name, convert in {
            "bgr": lambda f: f,
            "grey": lambda f: cv2.cvtColor(f, cv2.COLOR_BGR2GRAY),
            "grey HxWx1": lambda f: cv2.cvtColor(f, cv2.COLOR_BGR2GRAY)[:, :, np.newaxis],
            # rows of a wider image: read in place with its row stride
            "row view": lambda f: np.pad(f, ((0, 0), (0, 40), (0, 0)))[:, :640],
            # Fortran order and a flipped view: copied once
            "fortran": lambda f: np.asfortranarray(f),
            "flipped twice": lambda f: f[::-1][::-1],
        }.items():
            tracker.reset()  # each layout from the same start
            runs[name] = [tracker.track(convert(f)).world_to_camera for f in clip]
        for name in ("row view", "fortran", "flipped twice"):
            for a, b in zip(runs["bgr"], runs[name]):
                np.testing.assert_array_equal(a, b, err_msg=name)
        for a, b in zip(runs["grey"], runs["grey HxWx1"]):
            np.testing.assert_array_equal(a, b)
        self.assertTrue(any(T is not None for T in runs["grey"]))

    def test_parameters_from_a_dict_or_a_yaml_file(self):
        clip = frames()[:4]
        yaml = WORK / "params.yml"
        yaml.write_text("ransac: {max_iterations: &cap 90}  # flow map\n"
                        "relocalisation:\n  ransac_iterations: *cap\n")
        for params in ({"ransac": {"max_iterations": 90, "seed": np.int64(2)},
                        "correlation": {"min_score": np.float32(0.7)}}, yaml, str(yaml)):
            tracker = reftrack.Tracker.open_map(MAP, params=params)
            states = [tracker.track(f).state for f in clip]
            self.assertIn("tracking", states, params)

    def test_predicted_overlay_error_and_the_uncertain_state(self):
        # The predicted overlay error of the object given (a 10 cm cube on the marker, as the
        # recording draws it): a positive float while there is a pose. With a limit below it
        # (pose.max_predicted_error_px) each tracked frame is 'uncertain', its pose still given
        # and the same as without the limit (the tracker goes on from it).
        cube = np.array([[x, y, z] for x in (-0.05, 0.05) for y in (-0.05, 0.05)
                         for z in (0.0, 0.1)])
        clip = frames()[:5]
        plain = reftrack.Tracker.open_map(MAP, params={"pose": {"max_predicted_error_px": 0}})
        strict = reftrack.Tracker.open_map(MAP, params={"pose": {"max_predicted_error_px": 1e-4}})
        plain.set_overlay_points(cube)
        strict.set_overlay_points(cube)
        for frame in clip:
            p, s = plain.track(frame), strict.track(frame)
            self.assertEqual(p.state, "tracking", p.reason)
            self.assertIsInstance(p.predicted_error_px, float)
            self.assertGreater(p.predicted_error_px, 1e-4)
            self.assertEqual(s.state, "uncertain")
            self.assertIn("> pose.max_predicted_error_px 0.0001", s.reason)
            np.testing.assert_array_equal(s.world_to_camera, p.world_to_camera)
            self.assertEqual(s.predicted_error_px, p.predicted_error_px)
        # Another object, another prediction; 0x3 restores the default (the map's central box).
        plain.set_overlay_points(10 * cube)
        far = plain.track(clip[-1]).predicted_error_px
        plain.set_overlay_points(np.zeros((0, 3)))
        default = plain.track(clip[-1]).predicted_error_px
        self.assertNotAlmostEqual(far, default, places=6)
        with self.assertRaises(reftrack.Error):
            plain.set_overlay_points(np.array([[0.0, float("nan"), 0.0]]))

    def test_reset_starts_again_at_frame_0(self):
        tracker = reftrack.Tracker.open_map(MAP)
        clip = frames()[:3]
        for f in clip:
            tracker.track(f)
        tracker.reset()
        self.assertEqual(tracker.track(clip[0]).frame_index, 0)

    def test_homography_mode_against_one_reference(self):
        tracker = reftrack.Tracker.open_reference(CLIP / "reference_a.png",
                                                  camera=CLIP / "camera.yml")
        self.assertEqual(tracker.mode, "homography")
        reference = cv2.imread(str(CLIP / "reference_a.png"))
        r = tracker.track(reference)  # the reference itself: the identity
        self.assertEqual(r.state, "tracking", r.reason)
        np.testing.assert_allclose(r.homography / r.homography[2, 2], np.eye(3), atol=1e-3)
        self.assertEqual(r.world_to_camera.shape, (4, 4))  # rotation only, with a camera
        self.assertIsNone(r.covariance)
        self.assertIsNone(reftrack.Tracker.open_reference(CLIP / "reference_a.png")
                          .track(reference).world_to_camera)

    def test_bad_input_raises_a_clear_exception(self):
        tracker = reftrack.Tracker.open_map(MAP)
        frame = frames()[0]
        cases = [
            (lambda: tracker.track(frame.astype(np.float32)), TypeError,
             "frame must be a uint8 image, got dtype float32"),
            (lambda: tracker.track(frame.tolist()), TypeError, "frame must be a numpy array"),
            (lambda: tracker.track(np.zeros((480, 640, 4), np.uint8)), ValueError,
             "frame must be HxW (grey) or HxWx3 (BGR), got shape (480, 640, 4)"),
            (lambda: tracker.track(frame[:120, :160]), reftrack.Error,
             "tracker: frame is 160x120 but the map is 640x480"),
            (lambda: reftrack.Tracker.open_map(WORK / "absent"), reftrack.Error,
             "does not exist (run `reftrack prepare` first)"),
            (lambda: reftrack.Tracker.open_map(MAP, params={"ransac": {"max_iteratons": 80}}),
             reftrack.Error,
             "ransac.max_iteratons: unknown key — did you mean ransac.max_iterations?"),
            (lambda: reftrack.Tracker.open_map(MAP, params={"ransac": {"seed": float("nan")}}),
             reftrack.Error, "parameter 'ransac.seed' must be an integer"),
            (lambda: reftrack.Tracker.open_map(MAP, params={"ransac": {"seed": object()}}),
             TypeError, "parameters: ransac.seed is a object"),
            (lambda: reftrack.Tracker.open_map(MAP, params=3), TypeError,
             "params must be None, a YAML file's path or a dict, got int"),
            (lambda: reftrack.Tracker.open_reference(WORK / "none.png"), reftrack.Error,
             "reference image"),
        ]
        for call, kind, message in cases:
            with self.assertRaises(kind) as caught:
                call()
            self.assertIn(message, str(caught.exception))
        bad = WORK / "bad.yml"
        bad.write_text("mode: 6dof\n# tuned\nransac: {max_iteratons: 80}\n")
        with self.assertRaisesRegex(reftrack.Error, r"line 3: ransac\.max_iteratons: .* "
                                                    r"ransac\.max_iterations\?"):
            reftrack.Tracker.open_map(MAP, params=bad)
        self.assertTrue(issubclass(reftrack.Error, RuntimeError))
        self.assertEqual(tracker.track(frame).frame_index, 0)  # failed calls counted no frame

    def test_the_same_frames_give_the_same_poses_while_the_machine_is_busy(self):
        # The clip, twelve frames of noise (the search after the loss runs, then its budget holds
        # it back), and the clip again: tracked twice, the second time with both cores busy with
        # other processes. The search is budgeted in the modelled cost of its work (the default,
        # realtime=False), so the poses are the same to the byte.
        rng = np.random.default_rng(3)
        clip = frames()
        noise = [cv2.GaussianBlur(rng.integers(0, 256, clip[0].shape, dtype=np.uint8), (0, 0), 2)
                 for _ in range(12)]
        sequence = clip + noise + clip

        def play():
            tracker = reftrack.Tracker.open_map(MAP)
            out = []
            for frame in sequence:
                r = tracker.track(frame)
                out.append((r.state, r.reason, None if r.world_to_camera is None
                            else r.world_to_camera.tobytes()))
            return out

        quiet = play()
        burners = [subprocess.Popen([sys.executable, "-c", "while True: pass"])
                   for _ in range(max(2, os.cpu_count() or 2))]
        try:
            loaded = play()
        finally:
            for b in burners:
                b.kill()
                b.wait()
        self.assertGreaterEqual([s for s, _, _ in quiet].count("tracking"), FRAMES, quiet)
        self.assertTrue(any("budget" in reason for _, reason, _ in quiet), quiet)  # held back
        self.assertEqual(quiet, loaded)
        # realtime=True (a live camera) is accepted and tracks the same clip.
        live = reftrack.Tracker.open_map(MAP, realtime=True)
        self.assertEqual(live.track(clip[0]).state, "tracking")

if __name__ == "__main__":
    unittest.main(verbosity=2)
