#!/usr/bin/env bash
# Re-measures the recovery's cost model (engine/relocalisation/RecoveryWork.cpp,
# RecoveryCostModel::defaults): the milliseconds per unit of counted work that the relocalisation
# budget is charged on recorded input. On the shared real clips, one thread, each recovery's least
# CPU time of 3 plays: SIFT (the default) on the desk and shelf clips pooled, ORB and AKAZE on the
# desk's first 200 frames. Prints, per keypoint kind, how the current and the fitted model agree
# with the measured cost, and the fitted coefficients to put in RecoveryCostModel::defaults.
# Run it on a quiet machine (minutes). Usage: scripts/calibrate-recovery-cost.sh [BUILD_DIR] [OUT]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
out="${2:-$root/out/recovery-cost}"
reftrack="$build/app/reftrack"
data="$root/../shared/data"
desk="$data/desk-chessboard" shelf="$data/shelf-apriltags"
if [ ! -d "$desk/frames" ] || [ ! -d "$shelf/frames" ]; then
  echo "calibrate-recovery-cost: skipped: $desk or $shelf not found (the shared real recordings)"
  exit 0
fi
mkdir -p "$out"
for kind in sift orb akaze; do
  printf 'relocalisation:\n  keypoints: %s\n' "$kind" >"$out/$kind.yml"
  "$reftrack" prepare --input "$desk/frames" --ref-frames 0,40 --poses "$desk/groundtruth.txt" \
    --camera "$desk/camera.yml" --params "$out/$kind.yml" --out "$out/desk-$kind" >/dev/null
done
"$reftrack" prepare --input "$shelf/frames" --ref-frames 0,60 --poses "$shelf/groundtruth.txt" \
  --camera "$shelf/camera.yml" --out "$out/shelf-sift" >/dev/null
echo "== sift (desk + shelf)"
"$reftrack" bench-recovery-cost --map "$out/desk-sift" --input "$desk/frames" \
  --map "$out/shelf-sift" --input "$shelf/frames" --repeats 3 --csv "$out/sift.csv"
for kind in orb akaze; do
  echo "== $kind (desk, 200 frames)"
  "$reftrack" bench-recovery-cost --map "$out/desk-$kind" --input "$desk/frames" \
    --params "$out/$kind.yml" --frames 200 --repeats 2 --csv "$out/$kind.csv"
done
