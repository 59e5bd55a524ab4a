#!/usr/bin/env bash
# The desk clip in order (../shared/data/desk-chessboard, references 0/40 with their true poses),
# two builds side by side in one run, alternating so both see the same machine load: per run,
# `bench-real --methods reftrack --order sequence --passes 3` (median thread CPU per frame, one
# thread) and `track --out-csv` (median of the column ms_total, wall clock per frame, OpenCV's
# threads as a user has them). Prints every run, each build's median of the run medians, and the
# ratio other / this; then each stage's median (the CSV's ms_* columns: where a difference lies).
# Usage: scripts/compare-desk-speed.sh OTHER_REFTRACK [RUNS (default 4)]
# (this build: build/app/reftrack, or $REFTRACK_BUILD_DIR/app/reftrack).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
this="${REFTRACK_BUILD_DIR:-$root/build}/app/reftrack"
other="${1:?usage: compare-desk-speed.sh OTHER_REFTRACK [RUNS]}"
runs="${2:-4}"
desk="$root/../shared/data/desk-chessboard"
if [ ! -d "$desk/frames" ]; then
  echo "compare-desk-speed: skipped: $desk not found (the shared real recordings)"
  exit 0
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$this" prepare --input "$desk/frames" --ref-frames 0,40 --poses "$desk/groundtruth.txt" \
  --camera "$desk/camera.yml" --out "$work/map" >/dev/null
median_ms_total() {  # the median of the CSV column ms_total
  python3 -c '
import csv, statistics, sys
print("%.3f" % statistics.median(float(r["ms_total"]) for r in csv.DictReader(open(sys.argv[1]))))' "$1"
}
cpu_median() {  # bench-real's cpu_ms_med of the sequence row
  awk '$1 == "reftrack" && $2 == "sequence" { print $(NF - 1) }' "$1"
}
: >"$work/runs.txt"
for run in $(seq "$runs"); do
  for build in this other; do
    binary="$this"
    [ "$build" = other ] && binary="$other"
    "$binary" bench-real --input "$desk/frames" --camera "$desk/camera.yml" \
      --gt "$desk/groundtruth.txt" --ref-frames 0,40 --methods reftrack --order sequence \
      --passes 3 --out "$work/bench-$build-$run" >/dev/null 2>&1
    "$binary" track --map "$work/map" --input "$desk/frames" --out-csv "$work/$build-$run.csv" \
      >/dev/null 2>&1
    cpu="$(cpu_median "$work/bench-$build-$run/table.txt")"
    wall="$(median_ms_total "$work/$build-$run.csv")"
    echo "run $run $build: thread CPU median $cpu ms, ms_total median $wall ms"
    echo "$build $cpu $wall" >>"$work/runs.txt"
  done
done
python3 - "$work/runs.txt" <<'PY'
import statistics, sys
rows = [line.split() for line in open(sys.argv[1])]
m = {b: [statistics.median(float(r[i]) for r in rows if r[0] == b) for i in (1, 2)]
     for b in ("this", "other")}
for b in ("this", "other"):
    print(f"{b}: thread CPU {m[b][0]:.3f} ms, ms_total {m[b][1]:.3f} ms (medians of the runs)")
print(f"other / this: thread CPU x{m['other'][0] / m['this'][0]:.3f}, "
      f"ms_total x{m['other'][1] / m['this'][1]:.3f}")
PY
python3 - "$work" <<'PY'
import csv, glob, statistics, sys
def stages(build):  # per stage: the median over the runs of its per-frame median
    runs = [list(csv.DictReader(open(f))) for f in sorted(glob.glob(f"{sys.argv[1]}/{build}-*.csv"))]
    columns = [c for c in runs[0][0] if c.startswith("ms_")] if runs and runs[0] else []
    out = {}
    for c in columns:
        medians = [statistics.median(v) for v in
                   ([float(r[c]) for r in rows if r.get(c)] for rows in runs) if v]
        if medians:
            out[c] = statistics.median(medians)
    return out
this, other = stages("this"), stages("other")
print("stage medians (ms per frame; track, OpenCV's threads): stage this other")
for c in list(this) + [c for c in other if c not in this]:
    t, o = this.get(c), other.get(c)
    print(f"  {c[3:]:<16} {'-' if t is None else f'{t:.3f}':>7} {'-' if o is None else f'{o:.3f}':>7}")
PY
