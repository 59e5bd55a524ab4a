#!/usr/bin/env python3
"""Which of reftrack's large or under-predicted errors on a clip the per-frame peers share
(plain Python 3, no packages).

Usage: truth-limited-frames.py CUBE_ERRORS_CSV [ORDER] [--peer-px P] [--worse-px W] [--within-px D]
  CUBE_ERRORS_CSV  a clip's cube_errors.csv from `reftrack bench-real ... --methods
                   reftrack,sift,akaze --out DIR` (DIR/CLIP/cube_errors.csv)
  ORDER            the order's column suffix (default: sequence)
  --peer-px P      a frame is peer-limited when every peer in the file is more than P px off
                   (default 0.7): there the truth and the image disagree for any method
  --worse-px W     reftrack worse than its best peer by more than W px (default 0.4)
  --within-px D    coverage, over every frame with a true pose: per peer, the frames it posed
                   within D px and reftrack did not, and the other way (default 5: the suite's
                   'within 5 px'; issue 42's cold starts compare these counts)

Reported over the frames every method posed: the peer-limited frames; the frames where reftrack
is worse than its best peer; the frames whose true error exceeds 3x reftrack's predicted one, and
how many of them are peer-limited. Example (ViSP, repo root):
  reftrack bench-real --suite app/research/suites/real-clips.yml --clips visp-desk-apriltags \\
      --methods reftrack,sift,akaze --order sequence --out out/visp-peers
  scripts/truth-limited-frames.py out/visp-peers/visp-desk-apriltags/cube_errors.csv
"""
import argparse
import csv
import sys


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("order", nargs="?", default="sequence")
    parser.add_argument("--peer-px", type=float, default=0.7)
    parser.add_argument("--worse-px", type=float, default=0.4)
    parser.add_argument("--within-px", type=float, default=5.0)
    args = parser.parse_args()
    try:
        with open(args.csv, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        print(f"truth-limited-frames: cannot read {args.csv}: {e.strerror}", file=sys.stderr)
        return 1
    if not rows:
        print(f"truth-limited-frames: {args.csv} has no frames", file=sys.stderr)
        return 1
    suffix = f"_{args.order}_px"
    own = "reftrack" + suffix
    predicted = f"reftrack_{args.order}_predicted_px"
    peers = [k for k in rows[0] if k.endswith(suffix) and k != own]
    if own not in rows[0] or not peers:
        print(f"truth-limited-frames: {args.csv} needs the columns {own} and at least one peer's "
              f"*{suffix} (bench-real --methods reftrack,sift,... --order {args.order})",
              file=sys.stderr)
        return 1
    limited, worse, over3, over3_limited, frames = [], [], 0, 0, 0
    for r in rows:
        if not r[own] or any(not r[p] for p in peers):
            continue
        frames += 1
        true = float(r[own])
        best = min(float(r[p]) for p in peers)
        is_limited = best > args.peer_px
        if is_limited:
            limited.append(r["frame"])
        if true > best + args.worse_px:
            worse.append(f"{r['frame']} ({true:.2f} vs {best:.2f})")
        if r.get(predicted) and true > 3.0 * float(r[predicted]):
            over3 += 1
            over3_limited += is_limited
    print(f"{frames} frames posed by reftrack and every peer ({', '.join(p[:-len(suffix)] for p in peers)})")
    print(f"peer-limited (every peer > {args.peer_px} px): {len(limited)}: {' '.join(limited)}")
    print(f"reftrack > {args.worse_px} px worse than its best peer: {len(worse)}: {', '.join(worse)}")
    print(f"true > 3x predicted: {over3} ({100.0 * over3 / frames:.1f}%), of them peer-limited: "
          f"{over3_limited}; the others {over3 - over3_limited} "
          f"({100.0 * (over3 - over3_limited) / frames:.1f}%)")
    def within(r, column):
        return bool(r[column]) and float(r[column]) <= args.within_px

    for p in peers:
        only_peer = [r["frame"] for r in rows if within(r, p) and not within(r, own)]
        only_own = [r["frame"] for r in rows if within(r, own) and not within(r, p)]
        print(f"within {args.within_px:g} px: {p[:-len(suffix)]} {sum(within(r, p) for r in rows)}, "
              f"reftrack {sum(within(r, own) for r in rows)}; {p[:-len(suffix)]} only: "
              f"{len(only_peer)}: {' '.join(only_peer)}; reftrack only: {len(only_own)}: "
              f"{' '.join(only_own)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
