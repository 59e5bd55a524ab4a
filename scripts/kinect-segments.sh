#!/usr/bin/env bash
# The kinect-kitchen segments, each benchmarked on its own: reftrack beside SIFT + PnP, in order
# and shuffled as one sequence, with the map prepared from the segment's two references.
# Usage: kinect-segments.sh [OUT] [REFTRACK]   (OUT default /tmp/kinect-segments; REFTRACK default
# build/app/reftrack; SEGMENTS overrides the list "FIRST:LAST:REFA:REFB ..."; PREPARE_PARAMS, a
# `prepare --params` file for the maps).
# Per segment, OUT/<first>-<last>/ holds frames/ (symlinks to frames first..last renumbered from
# 000000), groundtruth.txt (those lines re-timed to (i - first) / 30), bench-real's table.txt and
# cube_errors.csv; the scored cube (edge 0.08 m) is centred 1 m in front of the first reference's
# true camera (its base centre half an edge lower in world z: bench-real's cube extends to +z).
# Last, one table: per segment, method and order, the frames within 5 px and the poses more than
# 20 px off (the Kinect's ground truth is good to 1-2.5 px only).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-/tmp/kinect-segments}"
reftrack="${2:-$root/build/app/reftrack}"
data="$root/../shared/data/kinect-kitchen"
segments="${SEGMENTS:-0:70:0:40 180:300:200:220 280:400:300:320}"
[ -d "$data/frames" ] || { echo "kinect-segments: $data/frames not found" >&2; exit 1; }
[ -x "$reftrack" ] || { echo "kinect-segments: $reftrack is not an executable" >&2; exit 1; }
mkdir -p "$out"
for s in $segments; do
  IFS=: read -r first last refA refB <<<"$s"
  dir="$out/$first-$last"
  rm -rf "$dir/frames"
  mkdir -p "$dir/frames"
  centre=$(python3 - "$data" "$dir" "$first" "$last" "$refA" <<'EOF'
import math, os, sys
data, out, first, last, ref = sys.argv[1], sys.argv[2], *map(int, sys.argv[3:6])
lines = [l.split() for l in open(os.path.join(data, "groundtruth.txt")) if not l.startswith("#")]
by_frame = {round(float(l[0]) * 30): l for l in lines}
with open(os.path.join(out, "groundtruth.txt"), "w") as gt:
    gt.write("# kinect-kitchen frames %d-%d re-timed to (i - %d) / 30\n" % (first, last, first))
    for i in range(first, last + 1):
        os.symlink(os.path.join(os.path.abspath(data), "frames", "%06d.jpg" % i),
                   os.path.join(out, "frames", "%06d.jpg" % (i - first)))
        if i in by_frame:
            gt.write("%.6f %s\n" % ((i - first) / 30.0, " ".join(by_frame[i][1:])))
t = list(map(float, by_frame[ref][1:4]))
x, y, z, w = map(float, by_frame[ref][4:8])
axis = [2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)]  # camera z in world
c = [t[i] + axis[i] for i in range(3)]
c[2] -= 0.04
print("%.6f,%.6f,%.6f" % tuple(c))
EOF
)
  echo "== segment $first-$last, references $refA/$refB, cube base centre $centre"
  "$reftrack" bench-real --input "$dir/frames" --camera "$data/camera.yml" \
    --gt "$dir/groundtruth.txt" --ref-frames "$((refA - first)),$((refB - first))" \
    --cube-centre="$centre" --cube-edge 0.08 --methods reftrack,sift \
    --order sequence,shuffled-sequence --out "$dir" \
    ${PREPARE_PARAMS:+--prepare-params "$PREPARE_PARAMS"} | tee "$dir/bench.log"
done
python3 - "$out" $segments <<'EOF'
import csv, math, os, sys
out = sys.argv[1]
print("%-10s %-10s %-18s %7s %7s %9s %8s" % ("segment", "method", "order", "frames", "posed",
                                            "<=5px", ">20px"))
for s in sys.argv[2:]:
    first, last, _, _ = s.split(":")
    rows = list(csv.DictReader(open(os.path.join(out, "%s-%s" % (first, last), "cube_errors.csv"))))
    for col in rows[0].keys():
        if col in ("frame", "true_pose") or "predicted" in col:
            continue
        name = col[:-3]  # "<method>_<order>_px"
        order = next(o for o in ("shuffled-sequence", "sequence", name) if name.endswith(o))
        method = name[:len(name) - len(order)].rstrip("_")
        vals = [r[col] for r in rows if r["true_pose"] == "1"]
        posed = [float(v) for v in vals if v != ""]
        print("%-10s %-10s %-18s %7d %7d %9d %8d" % (
            "%s-%s" % (first, last), method, order, len(vals), len(posed),
            sum(1 for e in posed if e <= 5.0), sum(1 for e in posed if not e <= 20.0)))
EOF
