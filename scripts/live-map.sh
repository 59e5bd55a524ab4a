#!/usr/bin/env bash
# Issue "build the map without leaving the viewer": the Map panel's headless path measured.
# 1. Simulator (handheld, marker DICT_6X6_250:23:0.2 in view): references captured at frames 0
#    and 30 from the marker, map built, the whole clip tracked; eval against the exact truth.
# 2. Real desk clip (../shared/data/desk-chessboard, skipped when absent): the world frame from
#    its own chessboard (--board chessboard:9x6:0.04), references at frames 0 and 40, no
#    ground-truth pose used; eval after aligning the two world frames (--align se3), and the
#    board-pose error of the two captured references against the clip's true poses.
# Usage: live-map.sh [--no-build]   (outputs in out/live-map)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${REFTRACK_BUILD_DIR:-$root/build}"
[[ "${1:-}" == "--no-build" ]] || bash "$root/scripts/build.sh" Release reftrack
reftrack="$build/app/reftrack"
out="$root/out/live-map"
mkdir -p "$out"

echo "== simulator: handheld, marker DICT_6X6_250:23:0.2, references at frames 0 and 30"
"$reftrack" simulate --preset handheld --out "$out/sim"
"$reftrack" view --headless --input "$out/sim/frames" --camera "$out/sim/camera.yml" \
  --marker DICT_6X6_250:23:0.2 --capture-at 0,30 --map-out "$out/sim-map" \
  --trajectory "$out/sim-trajectory.txt" | tee "$out/sim-view.txt"
"$reftrack" eval --gt "$out/sim/groundtruth.txt" --est "$out/sim-trajectory.txt" \
  --camera "$out/sim/camera.yml" --no-plots | tee "$out/sim-eval.txt"

desk="$root/../shared/data/desk-chessboard"
if [[ ! -d "$desk/frames" ]]; then
  echo "desk clip skipped: $desk not found (the shared real recordings)"
  exit 0
fi
echo "== desk clip: world frame from its chessboard 9x6 (4 cm), references at frames 0 and 40"
"$reftrack" view --headless --input "$desk/frames" --camera "$desk/camera.yml" \
  --board chessboard:9x6:0.04 --capture-at 0,40 --map-out "$out/desk-map" \
  --trajectory "$out/desk-trajectory.txt" | tee "$out/desk-view.txt"
echo "-- eval --align se3 (Umeyama on the camera centres)"
"$reftrack" eval --gt "$desk/groundtruth.txt" --est "$out/desk-trajectory.txt" \
  --camera "$desk/camera.yml" --align se3 --no-plots | tee "$out/desk-eval-se3.txt"
echo "-- eval --align se3-views (Umeyama on the centres and three points of each camera's view)"
"$reftrack" eval --gt "$desk/groundtruth.txt" --est "$out/desk-trajectory.txt" \
  --camera "$desk/camera.yml" --align se3-views --no-plots | tee "$out/desk-eval-se3-views.txt"
# The exact relation of the two world frames (README: the clip's world is the board's first inner
# corner with z toward the camera and the corners at y <= 0): world_gt = F world_board,
# F = diag(1, -1, -1), a half turn about x (quaternion x = 1).
python3 - "$out/desk-trajectory.txt" "$out/desk-trajectory-gtframe.txt" <<'PY'
import sys
with open(sys.argv[2], "w") as out:
    for line in open(sys.argv[1]):
        if line.startswith("#") or not line.strip():
            out.write(line)
            continue
        t, x, y, z, qx, qy, qz, qw = [float(v) for v in line.split()]
        out.write(f"{t:.6f} {x:.9f} {-y:.9f} {-z:.9f} {qw:.9f} {-qz:.9f} {qy:.9f} {-qx:.9f}\n")
PY
echo "-- eval in the clip's world frame by its exact relation to the board's (no fitted alignment)"
"$reftrack" eval --gt "$desk/groundtruth.txt" --est "$out/desk-trajectory-gtframe.txt" \
  --camera "$desk/camera.yml" --no-plots | tee "$out/desk-eval-exact.txt"
# Baseline in the same run: the same two references posed by the clip's true poses (`prepare
# --poses`, the README's way), tracked by `track`: the floor of either evaluation.
"$reftrack" prepare --input "$desk/frames" --ref-frames 0,40 --poses "$desk/groundtruth.txt" \
  --camera "$desk/camera.yml" --out "$out/desk-truth-map" >/dev/null
"$reftrack" track --input "$desk/frames" --map "$out/desk-truth-map" \
  --trajectory "$out/desk-truth-trajectory.txt" >/dev/null
echo "-- baseline: references posed by the true poses, eval --align se3 / se3-views / none"
for align in se3 se3-views none; do
  "$reftrack" eval --gt "$desk/groundtruth.txt" --est "$out/desk-truth-trajectory.txt" \
    --camera "$desk/camera.yml" --align "$align" --no-plots | grep -E "tracked|^cube"
done
# The captured references' board poses against the true poses (world_gt = F world_board).
python3 - "$out/desk-view.txt" "$desk/groundtruth.txt" <<'PY'
import math, sys
def rot(qx, qy, qz, qw):
    return [[1 - 2*(qy*qy + qz*qz), 2*(qx*qy - qz*qw), 2*(qx*qz + qy*qw)],
            [2*(qx*qy + qz*qw), 1 - 2*(qx*qx + qz*qz), 2*(qy*qz - qx*qw)],
            [2*(qx*qz - qy*qw), 2*(qy*qz + qx*qw), 1 - 2*(qx*qx + qy*qy)]]
gt = {}
for line in open(sys.argv[2]):
    if line.startswith('#') or not line.strip(): continue
    v = [float(x) for x in line.split()]
    gt[round(v[0], 4)] = (v[1:4], rot(*v[4:8]))
for line in open(sys.argv[1]):
    if not line.startswith('capture '): continue
    w = line.split()
    frame, t = int(w[3]), float(w[5])
    c = [float(x) for x in w[7:10]]
    R = rot(*[float(x) for x in w[11:15]])
    F = [1, -1, -1]
    c = [F[i] * c[i] for i in range(3)]
    R = [[F[i] * R[i][j] for j in range(3)] for i in range(3)]
    cg, Rg = gt[round(t, 4)]
    dpos = math.sqrt(sum((c[i] - cg[i]) ** 2 for i in range(3))) * 1000
    trace = sum(Rg[k][i] * R[k][i] for i in range(3) for k in range(3))  # trace(Rg^T R)
    ang = math.degrees(math.acos(max(-1.0, min(1.0, (trace - 1) / 2))))
    print(f"captured reference at frame {frame}: board pose vs true pose: centre {dpos:.2f} mm, "
          f"rotation {ang:.3f} deg")
PY

echo "== bad input (each must fail with a message and write nothing)"
bad() {
  local what="$1"; shift
  rm -rf "$out/bad-map" "$out/bad-trajectory.txt"
  local rc=0
  "$@" >"$out/bad.txt" 2>&1 || rc=$?
  [[ $rc -ne 0 ]] || { echo "FAIL: $what succeeded"; exit 1; }
  echo "$what: exit $rc, $(grep -i error "$out/bad.txt" | tail -1)"
  [[ ! -e "$out/bad-map" && ! -e "$out/bad-trajectory.txt" ]] || { echo "FAIL: output written"; exit 1; }
}
args=(view --headless --input "$desk/frames" --camera "$desk/camera.yml" --frames 5
  --map-out "$out/bad-map" --trajectory "$out/bad-trajectory.txt")
bad "board of the wrong size (8x6)" "$reftrack" "${args[@]}" --board chessboard:8x6:0.04 \
  --capture-at 0,40
bad "one capture" "$reftrack" "${args[@]}" --board chessboard:9x6:0.04 --capture-at 0
bad "two captures from the same place" "$reftrack" "${args[@]}" --board chessboard:9x6:0.04 \
  --capture-at 0,0
bad "no marker in view" "$reftrack" "${args[@]}" --marker DICT_6X6_250:23:0.2 --capture-at 0,40
# A full disk: a 200 KiB file-size limit (writes then fail with EFBIG, SIGXFSZ ignored).
bad "full disk on save" bash -c 'trap "" XFSZ; ulimit -f 200; exec "$@"' _ "$reftrack" \
  "${args[@]}" --board chessboard:9x6:0.04 --capture-at 0,40
