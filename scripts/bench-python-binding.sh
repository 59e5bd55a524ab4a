#!/usr/bin/env bash
# The Python binding's cost per frame: Python's time around Tracker.track() less the engine's own
# (Result.milliseconds), median over 200 calls on a simulated 640x480 clip (the Python tests'
# clip: tests/python/simulated_clip.py). Prints the median and fails above 0.1 ms. A timing, so
# a benchmark, not a test: run it on a quiet machine. Needs a build with the Python module
# (build/python) and the command (build/app/reftrack).
# Usage: scripts/bench-python-binding.sh [BUILD_DIR]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
# The Python the module was built for (Debian's), as CTest runs it.
py="$(sed -n 's/^Python_EXECUTABLE:FILEPATH=//p' "$build/CMakeCache.txt" 2>/dev/null)"
py="${py:-/usr/bin/python3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
REFTRACK_BINARY="$build/app/reftrack" REFTRACK_TEST_WORK="$work/clip" \
  PYTHONPATH="$build/python:$root/tests/python" PYTHONDONTWRITEBYTECODE=1 "$py" - <<'PY'
import statistics, time
import cv2, reftrack, simulated_clip
simulated_clip.make()
frames = [cv2.imread(str(p)) for p in sorted((simulated_clip.CLIP / "frames").glob("*.png"))]
tracker = reftrack.Tracker.open_map(simulated_clip.MAP)
overheads = []
for _ in range(10):
    tracker.reset()
    for frame in frames:
        start = time.perf_counter()
        r = tracker.track(frame)
        T = r.world_to_camera  # and reading the pose
        overheads.append(1000 * (time.perf_counter() - start) - r.milliseconds)
median = statistics.median(overheads)
q = statistics.quantiles(overheads, n=20)
print(f"binding overhead per frame: median {1000 * median:.1f} us (p5 {1000 * q[0]:.1f}, "
      f"p95 {1000 * q[-1]:.1f}) over {len(overheads)} calls")
raise SystemExit(0 if median < 0.1 else "above 0.1 ms")
PY
