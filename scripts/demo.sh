#!/usr/bin/env bash
# Set up, build (Release) and run the demo on the embedded default scene: no download, no camera.
# Simulates a handheld sequence, draws the cube at the replayed ground-truth pose and records
# DIR/demo.mp4 + DIR/demo_trajectory.txt; a window opens when a display exists (close it to
# finish), otherwise it runs headless. Usage: demo.sh [DIR] [extra `reftrack demo` options]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/setup.sh"
bash "$root/scripts/build.sh" Release
out="${1:-$root/demo-out}"
shift || true
"${REFTRACK_BUILD_DIR:-$root/build}/app/reftrack" demo --out "$out" "$@"
