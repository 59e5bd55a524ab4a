#!/usr/bin/env bash
# Soak benchmark: the viewer headless with live 6-DOF tracking and MP4 recording for FRAMES
# frames (default 20000): the demo's simulated 300-frame hand-held clip of the desk scene, encoded
# as MP4 and played in a loop (`view --loop`; each seam is a sudden jump the tracker must recover
# from), printing resident memory and frame rate every 1000 frames. Passes when, after a 1000-frame warm-up, memory grows by less
# than 2 MiB and the rate of the last 1000 frames is within 10% of the first 1000.
# Usage: soak.sh [FRAMES]   (REFTRACK_BUILD_DIR selects the build; SOAK_NO_BUILD=1 skips setup/build)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${REFTRACK_BUILD_DIR:-$root/build}"
frames="${1:-20000}"
if [[ ! "$frames" =~ ^[0-9]+$ ]] || (( frames < 3000 )); then
  echo "soak.sh: FRAMES must be a number >= 3000 (warm-up 1000 + two 1000-frame intervals)" >&2
  exit 2
fi
if [[ "${SOAK_NO_BUILD:-0}" != 1 ]]; then
  bash "$root/scripts/setup.sh"
  bash "$root/scripts/build.sh" Release
fi
out="$root/out/soak"
rm -rf "$out"
mkdir -p "$out"
reftrack="$build/app/reftrack"
# The demo's map and clip: demo.mp4 is the tracked overlay, so the clean frames are re-encoded.
"$reftrack" demo --headless --frames 300 --out "$out/scene" > "$out/demo.log"
seq="$out/scene/sequence"
clip="$out/clip.mp4"
ffmpeg -loglevel error -y -framerate 30 -i "$seq/frames/%06d.png" -c:v libx264 -crf 18 \
  -pix_fmt yuv420p "$clip"
loops=$(( (frames + 299) / 300 ))
log="$out/soak.log"
"$reftrack" view --headless --input "$clip" --camera "$seq/camera.yml" --loop "$loops" \
  --frames "$frames" --map "$out/scene/scene" --record "$out/soak.mp4" --report-every 1000 \
  --soak-warmup 1000 | tee "$log"
summary="$(grep '^soak: memory' "$log")"
growth="$(sed -E 's/.*growth ([-+0-9.]+) MiB.*/\1/' <<< "$summary")"
ratio="$(sed -E 's/.*fr\/s \(ratio ([0-9.]+)\);.*/\1/' <<< "$summary")"
cpu_ratio="$(sed -E 's/.*ms\/fr \(ratio ([0-9.]+)\).*/\1/' <<< "$summary")"
echo "soak.sh: $frames frames; memory growth after warm-up $growth MiB (limit 2);" \
  "last/first frame rate $ratio, CPU time per frame $cpu_ratio (limit 0.90-1.10)"
# The wall-clock rate is the issue's measure; on a shared machine other processes' load moves it,
# so the CPU time per frame (this process only) is judged beside it and a failure says which.
verdict=0
awk -v g="$growth" 'BEGIN { exit !(g < 2.0) }' || { echo "soak.sh: memory grew" >&2; verdict=1; }
awk -v r="$ratio" 'BEGIN { exit !(r >= 0.9 && r <= 1.1) }' ||
  { echo "soak.sh: the frame rate moved by more than 10% (check the machine's load)" >&2; verdict=1; }
awk -v r="$cpu_ratio" 'BEGIN { exit !(r >= 0.9 && r <= 1.1) }' ||
  { echo "soak.sh: CPU time per frame moved by more than 10%" >&2; verdict=1; }
if (( verdict == 0 )); then echo "soak.sh: PASS"; else echo "soak.sh: FAIL" >&2; exit 1; fi
