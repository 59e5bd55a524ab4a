#!/usr/bin/env bash
# Maps of unprepared scenes measured on real footage: each clip's two reference frames mapped
# WITHOUT their true poses (`prepare --unprepared --baseline B`, B the true distance between the
# two reference cameras, from the clip's groundtruth.txt) beside the same frames mapped from their
# true poses (`prepare --poses`), both tracked in order with defaults (`track`), both scored the
# same way (`eval --anchor-map`): the cube placed where the truth puts it relative to reference
# 0's camera, carried into each map's own world by that map's pose of reference 0, projected
# through every estimated pose and through the true one (mean px over its 8 vertices).
# Clips of ../shared/data (skipped when absent): desk-chessboard refs 0/40 (cube edge 0.1 at
# (0.16,-0.10,0)), visp-desk-apriltags 0/40 (edge 0.1 at (0.18,0.12,0)), kinect-kitchen 0/40 and
# 300/320 (edge 0.08 centred 1 m in front of reference 0's camera).
# Usage: unprepared-map.sh [--no-build] [CLIP...]   (outputs in out/unprepared-map; ~3 min)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${REFTRACK_BUILD_DIR:-$root/build}"
if [[ "${1:-}" == "--no-build" ]]; then
  shift
else
  bash "$root/scripts/build.sh" Release reftrack
fi
reftrack="$build/app/reftrack"
data="$root/../shared/data"
out="$root/out/unprepared-map"
mkdir -p "$out"

# name clip ref0 ref1 cube-edge cube-option
runs=(
  "desk desk-chessboard 0 40 0.1 --cube-at=0.16,-0.10,0"
  "visp visp-desk-apriltags 0 40 0.1 --cube-at=0.18,0.12,0"
  "kinect-0-40 kinect-kitchen 0 40 0.08 --cube-ahead=1"
  "kinect-300-320 kinect-kitchen 300 320 0.08 --cube-ahead=1"
)

# The distance between the camera centres of two frames of a TUM ground truth (t = index / 30).
baseline() {
  python3 - "$1" "$2" "$3" <<'PY'
import math, sys
poses = {}
for line in open(sys.argv[1]):
    if line.startswith("#") or not line.strip():
        continue
    v = [float(x) for x in line.split()]
    poses[round(v[0] * 30)] = v[1:4]
print(f"{math.dist(poses[int(sys.argv[2])], poses[int(sys.argv[3])]):.6f}")
PY
}

# field of `eval` output: tracked percentage, frames tracked, cube mean, cube p95
score() {
  local eval="$1"
  local tracked mean p95 frames
  tracked=$(grep -oE "tracked [0-9.]+%" "$eval" | grep -oE "[0-9.]+")
  frames=$(grep -oE "[0-9]+ associated" "$eval" | grep -oE "[0-9]+")
  mean=$(grep -oE "error: mean [0-9.]+" "$eval" | grep -oE "[0-9.]+$")
  p95=$(grep -oE "95th percentile [0-9.]+" "$eval" | grep -oE "[0-9.]+$")
  echo "$frames $tracked $mean $p95"
}

table="$out/table.txt"
printf "%-15s %-9s %-22s %-22s %s\n" "clip" "refs" "true-pose map" "unprepared map" \
  "unprepared / true" >"$table"
printf "%-15s %-9s %-22s %-22s %s\n" "" "" "tracked, cube mean/p95" "tracked, cube mean/p95" \
  "(cube mean)" >>"$table"
for run in "${runs[@]}"; do
  read -r name clip r0 r1 edge cube <<<"$run"
  if [[ $# -gt 0 && " $* " != *" $name "* ]]; then continue; fi
  dir="$data/$clip"
  if [[ ! -d "$dir/frames" ]]; then
    echo "$name skipped: $dir not found (the shared real recordings)"
    continue
  fi
  b=$(baseline "$dir/groundtruth.txt" "$r0" "$r1")
  t0=$(python3 -c "print($r0 / 30)")
  echo "== $name: references $r0/$r1, true baseline $b m"
  common=(--camera "$dir/camera.yml" --input "$dir/frames" --ref-frames "$r0,$r1")
  "$reftrack" prepare "${common[@]}" --poses "$dir/groundtruth.txt" --out "$out/$name-truth-map" \
    >"$out/$name-truth-prepare.txt"
  "$reftrack" prepare "${common[@]}" --unprepared --baseline "$b" --out "$out/$name-unprepared-map" \
    | tee "$out/$name-unprepared-prepare.txt" | grep -E "^(two-view|round|world|scale|pair)"
  for kind in truth unprepared; do
    "$reftrack" track --map "$out/$name-$kind-map" --input "$dir/frames" \
      --trajectory "$out/$name-$kind-trajectory.txt" >"$out/$name-$kind-track.txt"
    "$reftrack" eval --gt "$dir/groundtruth.txt" --est "$out/$name-$kind-trajectory.txt" \
      --camera "$dir/camera.yml" --cube "$edge" "$cube" --anchor-map "$out/$name-$kind-map" \
      --anchor-time "$t0" --no-plots >"$out/$name-$kind-eval.txt"
  done
  read -r tf tt tm tp <<<"$(score "$out/$name-truth-eval.txt")"
  read -r uf ut um up <<<"$(score "$out/$name-unprepared-eval.txt")"
  ratio=$(python3 -c "print(f'{$um / $tm:.2f}')")
  printf "%-15s %-9s %-22s %-22s %s\n" "$name" "$r0/$r1" "$tf ($tt%), $tm/$tp" \
    "$uf ($ut%), $um/$up" "$ratio" | tee -a "$table"
done
echo
cat "$table"
