#!/usr/bin/env bash
# HD speed (issue 14 item 4): median thread-CPU milliseconds per frame at 640x480, 1280x720 and
# 1920x1080, single thread, each against its baseline measured in the same run:
# - homography mode (`bench-homography`, simulated pan) vs ORB + BF + findHomography;
# - 6-DOF (`experiment-6dof`, handheld, the webcam effects) vs ORB + solvePnPRansac + Kalman.
# Usage: bench-hd.sh [frames]   (default 200 per size; sequences are cached in out/bench-hd/cache)
# Run it under `nice -n 10` on a shared machine; the cpu columns do not count other processes.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${REFTRACK_BUILD_DIR:-$root/build}"
frames="${1:-200}"
out="$root/out/bench-hd"
mkdir -p "$out"
reftrack="$build/app/reftrack"
[ -x "$reftrack" ] || bash "$root/scripts/build.sh" Release reftrack
"$reftrack" bench-homography --sizes 640x480 1280x720 1920x1080 --frames "$frames" 2>/dev/null |
  tee "$out/homography.txt"
for size in 640x480 1280x720 1920x1080; do
  "$reftrack" experiment-6dof --preset handheld --effects webcam --frames "$frames" --size "$size" \
    --no-fit-q --cache "$out/cache" --out "$out/6dof-$size" 2>/dev/null | tee "$out/6dof-$size.txt"
done
echo
echo "6-DOF, median thread CPU ms per frame (cpu_ms) and the baseline's in the same run:"
for size in 640x480 1280x720 1920x1080; do
  grep -E "^(regularised|ORB)" "$out/6dof-$size.txt" | while IFS= read -r line; do
    printf "%-10s %s cpu_ms %s\n" "$size" "${line:0:22}" "${line##* }"
  done
  grep "speed ratio" "$out/6dof-$size.txt" | sed "s/^/$size /"
done
