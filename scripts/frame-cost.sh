#!/usr/bin/env bash
# What a frame costs in order, not only the median: the shared clips with true poses (desk 0/40
# and 300/340, shelf 0/60, ViSP 0/40; ../shared/data), each played whole by `track --out-csv`
# (wall clock, OpenCV's threads), two builds alternating in one run so both see the same load.
# Per clip and build: the median over the runs of the median, mean, p95, p99 and max of ms_total,
# and the frames whose pose was put to the relocaliser's second opinion (column ms_confirm), with
# the median of that column.
# Usage: scripts/frame-cost.sh OTHER_REFTRACK [RUNS (default 2)]
# (this build: build/app/reftrack, or $REFTRACK_BUILD_DIR/app/reftrack).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
this="${REFTRACK_BUILD_DIR:-$root/build}/app/reftrack"
other="${1:?usage: frame-cost.sh OTHER_REFTRACK [RUNS]}"
runs="${2:-2}"
data="$root/../shared/data"
if [ ! -d "$data/desk-chessboard/frames" ]; then
  echo "frame-cost: skipped: $data not found (the shared real recordings)"
  exit 0
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
clips="desk-chessboard:0,40 desk-chessboard:300,340 shelf-apriltags:0,60 visp-desk-apriltags:0,40"
map_name() { local refs="${1#*:}"; echo "${1%%:*}-${refs/,/-}"; }  # desk-chessboard-0-40
for clip in $clips; do
  folder="${clip%%:*}"
  "$this" prepare --input "$data/$folder/frames" --ref-frames "${clip#*:}" \
    --poses "$data/$folder/groundtruth.txt" --camera "$data/$folder/camera.yml" \
    --out "$work/$(map_name "$clip").map" >/dev/null 2>&1
done
for run in $(seq "$runs"); do
  for clip in $clips; do
    folder="${clip%%:*}" name="$(map_name "$clip")"
    for build in this other; do
      binary="$this"
      [ "$build" = other ] && binary="$other"
      "$binary" track --map "$work/$name.map" --input "$data/$folder/frames" \
        --out-csv "$work/$name.$build.$run.csv" >/dev/null 2>&1
    done
  done
  echo "run $run of $runs done" >&2
done
python3 - "$work" $clips <<'PY'
import csv, glob, statistics, sys
work = sys.argv[1]
def summary(path):
    rows = list(csv.DictReader(open(path)))
    total = sorted(float(r["ms_total"]) for r in rows if r["ms_total"])
    at = lambda q: total[min(len(total) - 1, int(q * len(total)))]
    asked = [float(r["ms_confirm"]) for r in rows if r.get("ms_confirm")]
    return [statistics.median(total), statistics.mean(total), at(0.95), at(0.99), total[-1],
            len(asked), statistics.median(asked) if asked else 0.0]
print(f"{'clip':<28}{'build':<7}{'median':>8}{'mean':>8}{'p95':>8}{'p99':>8}{'max':>8}"
      "  second opinions (their median ms)")
for clip in sys.argv[2:]:
    folder, refs = clip.split(":")
    name = f"{folder}-{refs.replace(',', '-')}"
    means = {}
    for build in ("this", "other"):
        runs = [summary(p) for p in sorted(glob.glob(f"{work}/{name}.{build}.*.csv"))]
        m = [statistics.median(r[i] for r in runs) for i in range(7)]
        means[build] = m[1]
        print(f"{name:<28}{build:<7}" + "".join(f"{v:8.2f}" for v in m[:5]) +
              f"  {m[5]:.0f} ({m[6]:.1f})")
    print(f"{name:<28}mean other / this: x{means['other'] / means['this']:.2f}")
PY
