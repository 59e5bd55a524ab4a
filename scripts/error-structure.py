#!/usr/bin/env python3
"""Issue 33: what the cube error of a tracked real clip is made of (plain Python 3, no packages).

Usage: error-structure.py TRAJECTORY GROUNDTRUTH CAMERA_YML CX CY CZ EDGE
  TRAJECTORY   `reftrack track --trajectory` output (TUM, camera in world)
  GROUNDTRUTH  the clip's groundtruth.txt (TUM, camera in world; frame k at k / 30 s)
  CAMERA_YML   its camera.yml (camera_matrix; the cube is projected with K alone, as bench-real)
  CX CY CZ     centre of the cube's base (world, m); EDGE its edge (m), extending to +z

Per frame, the error vectors (estimate - truth) of the cube's 8 projected vertices. Reported: the
mean cube error; the error's mean square and its white (frame-to-frame independent) part, from
the mean square of its second differences / 6; the truth's and the estimate's own second
differences (true motion plus each one's jitter: their difference / 6 is the truth's jitter
variance minus the estimate's); the error's autocorrelation at a few lags; and how much of the
error follows the image velocity (a lagging estimate). Example (desk, repo root):
  reftrack track --input ../shared/data/desk-chessboard/frames --map MAP --trajectory t.txt
  scripts/error-structure.py t.txt ../shared/data/desk-chessboard/groundtruth.txt \
      ../shared/data/desk-chessboard/camera.yml 0.16 -0.10 0 0.1
"""
import math
import re
import sys


def camera_matrix(path):
    text = open(path).read()
    block = text[text.index("camera_matrix"):]
    data = block[block.index("[") + 1:block.index("]")]
    v = [float(x) for x in re.split(r"[,\s]+", data.strip()) if x]
    return v[0], v[4], v[2], v[5]  # fx, fy, cx, cy


def rotation(qx, qy, qz, qw):
    return [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
            [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
            [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]]


def trajectory(path):
    poses = {}
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        v = [float(x) for x in line.split()]
        poses[round(v[0] * 30)] = (v[1:4], rotation(*v[4:8]))
    return poses


def project(K, pose, X):
    t, R = pose  # camera in world: X_cam = R^T (X - t)
    d = [X[i] - t[i] for i in range(3)]
    c = [sum(R[j][i] * d[j] for j in range(3)) for i in range(3)]
    return K[0] * c[0] / c[2] + K[2], K[1] * c[1] / c[2] + K[3]


def mean(xs):
    return sum(xs) / len(xs)


def main():
    if len(sys.argv) != 8:
        sys.exit(__doc__)
    est, gt = trajectory(sys.argv[1]), trajectory(sys.argv[2])
    K = camera_matrix(sys.argv[3])
    cx, cy, cz, e = (float(x) for x in sys.argv[4:8])
    cube = [(cx + sx * e / 2, cy + sy * e / 2, cz + sz * e)
            for sx in (-1, 1) for sy in (-1, 1) for sz in (0, 1)]
    frames = sorted(k for k in est if k in gt)
    if len(frames) < 3:
        sys.exit("fewer than 3 frames with both a pose and a true pose")
    P = {k: [project(K, est[k], X) for X in cube] for k in frames}
    T = {k: [project(K, gt[k], X) for X in cube] for k in frames}
    err = {k: [(a[0] - b[0], a[1] - b[1]) for a, b in zip(P[k], T[k])] for k in frames}

    def second_differences(S):
        return [mean([(S[k - 1][i][0] - 2 * S[k][i][0] + S[k + 1][i][0]) ** 2 +
                      (S[k - 1][i][1] - 2 * S[k][i][1] + S[k + 1][i][1]) ** 2 for i in range(8)])
                for k in frames if k - 1 in S and k + 1 in S]

    ms = mean([mean([x * x + y * y for x, y in err[k]]) for k in frames])
    white = mean(second_differences(err)) / 6
    truth_d2 = mean(second_differences(T)) / 6
    est_d2 = mean(second_differences(P)) / 6
    print("frames %d, mean cube error %.3f px" %
          (len(frames), mean([mean([math.hypot(x, y) for x, y in err[k]]) for k in frames])))
    print("error mean square %.4f px^2; white part %.4f (%.0f%%)" % (ms, white, 100 * white / ms))
    print("second differences / 6: truth %.4f, estimate %.4f px^2 (truth jitter minus the "
          "estimate's: %.4f)" % (truth_d2, est_d2, truth_d2 - est_d2))
    for lag in (1, 2, 5, 10, 30):
        cov = [mean([err[k][i][0] * err[k + lag][i][0] + err[k][i][1] * err[k + lag][i][1]
                     for i in range(8)]) for k in frames if k + lag in err]
        print("autocorrelation at lag %2d: %.3f" % (lag, mean(cov) / ms))
    sxy = sxx = syy = 0.0
    for k in frames:
        if k - 1 in T and k + 1 in T:
            for i in range(8):
                for a in range(2):
                    v = (T[k + 1][i][a] - T[k - 1][i][a]) / 2
                    sxy += v * err[k][i][a]
                    sxx += v * v
                    syy += err[k][i][a] ** 2
    c = sxy / sxx
    print("error = %.4f x image velocity: explains %.1f%% of the error" %
          (c, 100 * c * c * sxx / syy))


if __name__ == "__main__":
    main()
