#!/usr/bin/env bash
# Set up, build (Release) and run the demo on the embedded default scene: no download, no camera.
# Simulates a handheld sequence, prepares the reference map from the marker, tracks every frame
# in full 6-DOF, records the registered cube as DIR/demo.mp4 + DIR/demo_trajectory.txt and prints
# the evaluation against ground truth; a window opens when a display exists (close it to finish),
# otherwise it runs headless. Usage: demo.sh [DIR] [extra `reftrack demo` options]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/setup.sh"
# Only the `reftrack` CLI and its libraries: the test suite is built by scripts/test.sh.
bash "$root/scripts/build.sh" Release reftrack
out="${1:-$root/demo-out}"
shift || true
"${REFTRACK_BUILD_DIR:-$root/build}/app/reftrack" demo --out "$out" "$@"
