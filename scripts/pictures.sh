#!/usr/bin/env bash
# Regenerates the README's pictures in assets/readme/ from the shared real clips (skipped, with a
# message, when ../shared/data is absent): the per-frame cube error of reftrack beside the best
# per-frame OpenCV peer (`bench-real`, sequence order) on the desk clip (references 0/40) and on
# the shelf clip (references 0/60). Takes ~10 minutes on 2 cores (the peers are slow).
# Usage: scripts/pictures.sh
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${REFTRACK_BUILD_DIR:-$root/build}"
data="$root/../shared/data"
out="$root/assets/readme"
bash "$root/scripts/build.sh" Release reftrack >/dev/null
mkdir -p "$out"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# bench-real on one clip, its plot copied to $out/NAME.png: NAME FOLDER REFS CUBE_CENTRE CUBE_EDGE
plot_clip() {
  local name="$1" clip="$data/$2"
  if [[ ! -d "$clip/frames" ]]; then
    echo "pictures: $name skipped: $clip not found (the shared real recordings)"
    return
  fi
  "$build/app/reftrack" bench-real --input "$clip/frames" --camera "$clip/camera.yml" \
    --gt "$clip/groundtruth.txt" --ref-frames "$3" --cube-centre "$4" --cube-edge "$5" \
    --methods reftrack,sift,akaze,orb --order sequence --out "$work/$name" >"$work/$name.log"
  cp "$work/$name/cube_errors.png" "$out/$name.png"
  echo "pictures: wrote $out/$name.png"
}

plot_clip desk-cube-errors desk-chessboard 0,40 0.16,-0.10,0 0.1
plot_clip shelf-cube-errors shelf-apriltags 0,60 0.1,0.2,-0.12 0.05
