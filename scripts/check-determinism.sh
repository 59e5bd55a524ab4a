#!/usr/bin/env bash
# Same input, same output: recorded input gives byte-identical results on any machine load. Each
# way of tracking a recording runs twice — alone, then with a CPU-burning process on every core
# beside it — and its output of the two runs is compared byte for byte (cmp):
#   track            `track --trajectory` (TUM poses)
#   view             `view --headless --trajectory`
#   bench-real       `bench-real --input --methods reftrack --order cuts:8`: cube_errors.csv (one
#                    row per frame, the pose's cube error: any pose change shows)
#   python           the Python module's poses (reftrack.Tracker, world_to_camera bytes)
#   track-realtime   `track --realtime` (budgeted in measured CPU time, as a live camera): shown for
#                    comparison, its difference is expected and not a failure
# The input: the desk clip of ../shared/data (references 0/40 with their true poses) as a folder
# of 120 frames with two cuts — desk frames 0-39, 40 frames of the shelf clip (another scene: the
# search after the loss runs, then its budget holds it back), desk frames 300-339 (found again by
# the relocaliser) — so the relocalisation budget decides on every run.
# Usage: scripts/check-determinism.sh [BUILD_DIR]   (exit 1 when a comparison differs)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
reftrack="$build/app/reftrack"
data="$root/../shared/data"
desk="$data/desk-chessboard" shelf="$data/shelf-apriltags"
if [ ! -d "$desk/frames" ] || [ ! -d "$shelf/frames" ]; then
  echo "check-determinism: skipped: $desk or $shelf not found (the shared real recordings)"
  exit 0
fi
[ -x "$reftrack" ] || { echo "check-determinism: $reftrack not built" >&2; exit 1; }
# The Python the module was built for (Debian's), as CTest runs it.
py="$(sed -n 's/^Python_EXECUTABLE:FILEPATH=//p' "$build/CMakeCache.txt" 2>/dev/null)"
py="${py:-/usr/bin/python3}"
work="$(mktemp -d)"
burners=()
stop_burners() {
  for pid in "${burners[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${burners[@]}"; do wait "$pid" 2>/dev/null || true; done
  burners=()
}
trap 'stop_burners; rm -rf "$work"' EXIT
start_burners() {
  for _ in $(seq "$(nproc)"); do
    bash -c 'while :; do :; done' &
    burners+=($!)
  done
}

mkdir -p "$work/clip"
n=0
link() { ln -s "$1" "$(printf '%s/clip/%06d.jpg' "$work" "$n")"; n=$((n + 1)); }
for i in $(seq 0 39); do link "$(printf '%s/frames/%06d.jpg' "$desk" "$i")"; done
for i in $(seq 0 39); do link "$(printf '%s/frames/%06d.jpg' "$shelf" "$i")"; done
for i in $(seq 300 339); do link "$(printf '%s/frames/%06d.jpg' "$desk" "$i")"; done
"$reftrack" prepare --input "$desk/frames" --ref-frames 0,40 --poses "$desk/groundtruth.txt" \
  --camera "$desk/camera.yml" --out "$work/map" >/dev/null

# run NAME OUTPUT COMMAND...: the command alone, then under load; cmp of OUTPUT ({run} in the
# command and OUTPUT is the run's own folder).
failed=0
run() {
  local name="$1" output="$2"
  shift 2
  for run in quiet loaded; do
    mkdir -p "$work/$name/$run"
    [ "$run" = loaded ] && start_burners
    local args=("${@//\{run\}/$work/$name/$run}")
    "${args[@]}" >"$work/$name/$run/stdout.txt" 2>&1 ||
      { stop_burners; echo "$name ($run) failed:"; tail -5 "$work/$name/$run/stdout.txt"; exit 1; }
    stop_burners
  done
  local a="${output//\{run\}/$work/$name/quiet}" b="${output//\{run\}/$work/$name/loaded}"
  if cmp -s "$a" "$b"; then
    echo "$name: identical ($(wc -l <"$a") lines) alone and with $(nproc) busy cores beside it"
    return 0
  fi
  echo "$name: DIFFERENT alone and under load: $(cmp "$a" "$b" | head -1)"
  return 1
}

run track "{run}/traj.txt" "$reftrack" track --map "$work/map" --input "$work/clip" \
  --trajectory "{run}/traj.txt" --out-csv "{run}/frames.csv" || failed=1
grep -o "relocalisation: .*" "$work/track/quiet/stdout.txt" || true
run view "{run}/traj.txt" "$reftrack" view --headless --input "$work/clip" \
  --camera "$desk/camera.yml" --map "$work/map" --trajectory "{run}/traj.txt" || failed=1
run bench-real "{run}/out/cube_errors.csv" "$reftrack" bench-real --input "$desk/frames" \
  --camera "$desk/camera.yml" --gt "$desk/groundtruth.txt" --ref-frames 0,40 \
  --cube-centre 0.16,-0.10,0 --cube-edge 0.1 --methods reftrack --order cuts:8 --frames 160 \
  --out "{run}/out" || failed=1
cat >"$work/poses.py" <<'PY'
import pathlib, sys
import cv2, reftrack
tracker = reftrack.Tracker.open_map(sys.argv[1])
with open(sys.argv[3], "wb") as out:
    for path in sorted(pathlib.Path(sys.argv[2]).glob("*.jpg")):
        r = tracker.track(cv2.imread(str(path)))
        out.write(r.state.encode() + b"\n")
        if r.world_to_camera is not None:
            out.write(r.world_to_camera.tobytes())
PY
if [ -d "$build/python" ]; then
  run python "{run}/poses.bin" env PYTHONPATH="$build/python" "$py" "$work/poses.py" \
    "$work/map" "$work/clip" "{run}/poses.bin" || failed=1
else
  echo "python: skipped (no Python module in $build/python)"
fi
if run track-realtime "{run}/traj.txt" "$reftrack" track --realtime --map "$work/map" \
  --input "$work/clip" --trajectory "{run}/traj.txt"; then
  :
else
  echo "  (expected: --realtime budgets in measured CPU time, which the load changes)"
fi
exit "$failed"
