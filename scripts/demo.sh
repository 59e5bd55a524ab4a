#!/usr/bin/env bash
# Set up, build (Release) and run the demo on the embedded default scene: no download, no camera.
# Outputs go to demo-out/ (or the folder given as the first argument).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/setup.sh"
bash "$root/scripts/build.sh" Release
out="${1:-$root/demo-out}"
"${REFTRACK_BUILD_DIR:-$root/build}/app/reftrack" demo --out "$out"
