#!/usr/bin/env bash
# Relocalisation's cost and reach on real footage at 640x480: the shared desk clip cropped to its
# central 640x480 (the camera's principal point moved with the crop), a map prepared from frames
# 0 and 40 with their true poses, then `track --cold-starts` (every frame a cold start: the start
# near a reference or a relocalisation) prints the attempts, how many were verified and their
# median time. Then the same at the clip's own 752x480. Skipped, with a message, without
# ../shared/data. Usage: scripts/bench-relocalisation.sh [extra `track` options, e.g. --params F]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${REFTRACK_BUILD_DIR:-$root/build}"
clip="$root/../shared/data/desk-chessboard"
if [[ ! -d "$clip/frames" ]]; then
  echo "bench-relocalisation: skipped: $clip not found (the shared real recordings)"
  exit 0
fi
bash "$root/scripts/build.sh" Release reftrack >/dev/null
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
reftrack="$build/app/reftrack"

# The crop: columns 56 .. 695 of 752 (cx - 56), lossless PNG.
mkdir -p "$work/crop"
ffmpeg -loglevel error -start_number 0 -i "$clip/frames/%06d.jpg" -vf crop=640:480:56:0 \
  -start_number 0 "$work/crop/%06d.png"
sed -e 's/^image_width: 752/image_width: 640/' \
  -e 's/3\.5520829800000001e+02/2.9920829800000001e+02/' "$clip/camera.yml" >"$work/camera640.yml"
grep -q '2.9920829800000001e+02' "$work/camera640.yml" ||
  { echo "bench-relocalisation: the camera file's cx was not found to move" >&2; exit 1; }

run() {  # NAME FRAMES CAMERA
  "$reftrack" prepare --input "$2" --ref-frames 0 40 --poses "$clip/groundtruth.txt" \
    --camera "$3" --out "$work/map_$1" >"$work/prepare_$1.log"
  echo "== $1"
  "$reftrack" track --input "$2" --map "$work/map_$1" --out-csv "$work/track_$1.csv" \
    --cold-starts "${@:4}" | grep -E '^(6dof|relocalisation|recovery)'
}
run 640x480 "$work/crop" "$work/camera640.yml" "$@"
run 752x480 "$clip/frames" "$clip/camera.yml" "$@"
