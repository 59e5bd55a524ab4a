#!/usr/bin/env bash
# Speed and accuracy benchmarks (single thread), each against its baseline measured in the same
# run: homography mode vs ORB + findHomography, 6-DOF vs ORB + solvePnPRansac + KalmanFilter;
# issue 13: the walkaround with N references (and its two-reference coverage), cold start,
# kidnapped camera and the cost of N references vs two (ORB + solvePnPRansac cold start beside);
# issue 14: 6-DOF on the real postcard clip (../shared/data, skipped when absent) vs ORB + PnP;
# issue 24: the real desk clip with true poses (../shared/data/desk-chessboard, skipped when
# absent): reftrack vs SIFT / AKAZE / ORB + PnP per frame and ORB + PnP + Kalman, in sequence and
# shuffled order (table, CSV and plot in out/bench/desk-chessboard); every real clip with true
# poses (app/research/suites/real-clips.yml: `bench-real --suite`, peers cached in
# out/peer-cache; one table, files in out/bench/real-clips).
# Usage: bench.sh [frames]   (default 300 frames per 6-DOF sequence; the walkaround runs 1000)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${REFTRACK_BUILD_DIR:-$root/build}"
frames="${1:-300}"
bash "$root/scripts/setup.sh"
bash "$root/scripts/build.sh" Release
out="$root/out/bench"
mkdir -p "$out"
"$build/app/reftrack" bench-homography
for size in 320x240 640x480; do
  "$build/app/reftrack" experiment-6dof --preset handheld --frames "$frames" --size "$size" \
    --out "$out/6dof-handheld-$size"
done
"$build/app/reftrack" experiment-6dof --preset static --frames "$frames" --no-baseline \
  --out "$out/6dof-static"
"$build/app/reftrack" experiment-6dof --preset walkaround --frames 1000 --references 6 \
  --no-baseline --out "$out/6dof-walkaround"
"$build/app/reftrack" experiment-relocalisation --references 8 --cold-starts 200 --kidnaps 100 \
  --out-csv "$out/relocalisation.csv"
postcard="$root/../shared/data/planar-videos/video-postcard.mp4"
if [[ -f "$postcard" ]]; then
  "$build/app/reftrack" bench-real --clip "$postcard" --passes 5
else
  echo "bench-real skipped: $postcard not found (the shared real recordings)"
fi
desk="$root/../shared/data/desk-chessboard"
if [[ -d "$desk/frames" ]]; then
  "$build/app/reftrack" bench-real --input "$desk/frames" --camera "$desk/camera.yml" \
    --gt "$desk/groundtruth.txt" --ref-frames 0,40 --cube-centre 0.16,-0.10,0 --cube-edge 0.1 \
    --out "$out/desk-chessboard"
else
  echo "bench-real --input skipped: $desk not found (the shared real recordings)"
fi
data="$root/../shared/data"
if [[ -d "$data" ]]; then
  "$build/app/reftrack" bench-real --suite "$root/app/research/suites/real-clips.yml" \
    --data "$data" --peer-cache "$root/out/peer-cache" --out "$out/real-clips"
else
  echo "bench-real --suite skipped: $data not found (the shared real recordings)"
fi
# HD speed: homography and 6-DOF at 640x480, 1280x720 and 1920x1080 (thread CPU, baselines beside)
bash "$root/scripts/bench-hd.sh" "$frames"
