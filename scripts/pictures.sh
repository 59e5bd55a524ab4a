#!/usr/bin/env bash
# Regenerates the README's pictures in assets/readme/ (each <= 600 kB):
#   viewer             the viewer with its panels (`view --headless --ui`) tracking the embedded demo
#                      scene (`sim:handheld`) against the map `reftrack prepare` makes from its
#                      two reference images (~1 min)
#   desk-overlay       a frame of the registered cube on the real desk clip (references 0 and 40
#                      with their true poses; `view --headless`, ~10 s)
#   desk-cube-errors   the per-frame cube error of reftrack beside the best per-frame OpenCV peer
#                      (`bench-real`, sequence order) on the desk clip (references 0/40)
#   shelf-cube-errors  the same on the shelf clip (references 0/60)
# The last three need the shared real clips (../shared/data) and are skipped, with a message, when
# they are absent; the two bench-real plots take ~10 minutes on 2 cores (the peers are slow).
# Usage: scripts/pictures.sh [NAME...]   (default: all four)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${REFTRACK_BUILD_DIR:-$root/build}"
data="$root/../shared/data"
out="$root/assets/readme"
max_bytes=$((600 * 1024))
wanted=("$@")
[[ ${#wanted[@]} -eq 0 ]] && wanted=(viewer desk-overlay desk-cube-errors shelf-cube-errors)
want() {
  local w
  for w in "${wanted[@]}"; do [[ "$w" == "$1" ]] && return 0; done
  return 1
}
for w in "${wanted[@]}"; do
  case "$w" in
    viewer | desk-overlay | desk-cube-errors | shelf-cube-errors) ;;
    *)
      echo "pictures: unknown picture '$w' (viewer, desk-overlay, desk-cube-errors, shelf-cube-errors)" >&2
      exit 2
      ;;
  esac
done
bash "$root/scripts/build.sh" Release reftrack >/dev/null
reftrack="$build/app/reftrack"
mkdir -p "$out"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# A screenshot (PNG) stored as $out/NAME.jpg, refused when larger than the README's limit.
store_jpeg() {
  local png="$1" name="$2"
  ffmpeg -y -loglevel error -i "$png" -q:v 3 "$work/$name.jpg"
  local bytes
  bytes=$(stat -c %s "$work/$name.jpg")
  if ((bytes > max_bytes)); then
    echo "pictures: $name.jpg is $bytes bytes, above $max_bytes" >&2
    exit 1
  fi
  mv "$work/$name.jpg" "$out/$name.jpg"
  echo "pictures: wrote $out/$name.jpg ($((bytes / 1024)) kB)"
}

# The cube where the picture wants it: with the viewer's --cube-at / --cube-edge when this build
# has them, else through the `overlay` section of a parameter file (debug layers off).
cube_options() {  # X,Y,Z EDGE -> options appended to the array `cube`
  cube=()
  if "$reftrack" view --help | grep -q -- '--cube-at'; then
    cube=(--cube-at "$1" --cube-edge "$2")
  else
    local x y z
    IFS=, read -r x y z <<<"$1"
    printf 'overlay:\n  size: %s\n  offset_x: %s\n  offset_y: %s\n  offset_z: %s\n  show_corners: 0\n  show_matches: 0\n' \
      "$2" "$x" "$y" "$z" >"$work/overlay.yml"
    cube=(--params "$work/overlay.yml")
  fi
}

# The viewer and its panels on the embedded demo scene: the map from the simulator's two reference
# images and marker (as the demo prepares it), then the simulated hand-held camera tracked live.
if want viewer; then
  "$reftrack" simulate --preset handheld --frames 1 --out "$work/sim" >"$work/simulate.log"
  "$reftrack" prepare --camera "$work/sim/camera.yml" --ref "$work/sim/reference_a.png" \
    --ref "$work/sim/reference_b.png" --marker DICT_6X6_250:23:0.2 --out "$work/sim-map" \
    >"$work/prepare-sim.log"
  "$reftrack" view --headless --ui --input sim:handheld --sim-frames 90 --map "$work/sim-map" \
    --frames 90 --screenshot "$work/viewer.png" >"$work/view-sim.log" 2>&1
  store_jpeg "$work/viewer.png" viewer
fi

# The registered cube on real footage: the desk clip, its map from frames 0 and 40 with their
# true poses, the cube on the chessboard's centre; frame 199 (hands out of view).
desk="$data/desk-chessboard"
if want desk-overlay; then
  if [[ ! -d "$desk/frames" ]]; then
    echo "pictures: desk-overlay skipped: $desk not found (the shared real recordings)"
  else
    "$reftrack" prepare --input "$desk/frames" --ref-frames 0,40 --poses "$desk/groundtruth.txt" \
      --camera "$desk/camera.yml" --out "$work/desk-map" >"$work/prepare-desk.log"
    cube_options 0.16,-0.10,0 0.1
    "$reftrack" view --headless --input "$desk/frames" --camera "$desk/camera.yml" \
      --map "$work/desk-map" "${cube[@]}" --frames 200 --screenshot "$work/desk-overlay.png" \
      >"$work/view-desk.log" 2>&1
    store_jpeg "$work/desk-overlay.png" desk-overlay
  fi
fi

# bench-real on one clip, its plot copied to $out/NAME.png: NAME FOLDER REFS CUBE_CENTRE CUBE_EDGE
plot_clip() {
  local name="$1" clip="$data/$2"
  want "$name" || return 0
  if [[ ! -d "$clip/frames" ]]; then
    echo "pictures: $name skipped: $clip not found (the shared real recordings)"
    return
  fi
  "$reftrack" bench-real --input "$clip/frames" --camera "$clip/camera.yml" \
    --gt "$clip/groundtruth.txt" --ref-frames "$3" --cube-centre "$4" --cube-edge "$5" \
    --methods reftrack,sift,akaze,orb --order sequence --out "$work/$name" >"$work/$name.log"
  cp "$work/$name/cube_errors.png" "$out/$name.png"
  echo "pictures: wrote $out/$name.png"
}

plot_clip desk-cube-errors desk-chessboard 0,40 0.16,-0.10,0 0.1
plot_clip shelf-cube-errors shelf-apriltags 0,60 0.1,0.2,-0.12 0.05
