#include "engine/features/SubPixelCorner.hpp"

#include <cmath>

#include "engine/core/Error.hpp"

namespace reftrack {

void refineCornersSubPixel(const cv::Mat& gray, std::vector<cv::Point2f>& points, int halfWindow) {
  if (gray.empty() || gray.type() != CV_8UC1)
    throw Error("sub-pixel corners: expected a non-empty 8-bit grey image");
  if (halfWindow < 1) throw Error("sub-pixel corners: the half window must be at least 1");
  const int h = halfWindow, side = 2 * h + 1;
  // cv::cornerSubPix's weights: exp(-(u^2 + v^2)) with u, v the offsets scaled to [-1, 1].
  std::vector<double> weight(static_cast<size_t>(side * side));
  for (int v = -h; v <= h; ++v)
    for (int u = -h; u <= h; ++u)
      weight[static_cast<size_t>((v + h) * side + u + h)] =
          std::exp(-(static_cast<double>(u * u + v * v)) / (h * h));
  constexpr int kMaxRecentres = 4;
  for (cv::Point2f& point : points) {
    const cv::Point2f start = point;
    cv::Point2d p(point.x, point.y);
    bool ok = false;
    for (int round = 0; round < kMaxRecentres; ++round) {
      const int cx = static_cast<int>(std::lround(p.x)), cy = static_cast<int>(std::lround(p.y));
      if (cx - h - 1 < 0 || cy - h - 1 < 0 || cx + h + 1 >= gray.cols || cy + h + 1 >= gray.rows)
        break;
      // Doubled central differences (exact integers); the factor 2 cancels in the solution.
      double a = 0, b = 0, c = 0, bx = 0, by = 0;
      for (int v = -h; v <= h; ++v) {
        const uchar* up = gray.ptr<uchar>(cy + v - 1);
        const uchar* row = gray.ptr<uchar>(cy + v);
        const uchar* down = gray.ptr<uchar>(cy + v + 1);
        const double* w = &weight[static_cast<size_t>((v + h) * side)];
        for (int u = -h; u <= h; ++u) {
          const int x = cx + u;
          const double gx = row[x + 1] - row[x - 1], gy = down[x] - up[x];
          const double wxx = w[u + h] * gx * gx, wxy = w[u + h] * gx * gy, wyy = w[u + h] * gy * gy;
          a += wxx;
          b += wxy;
          c += wyy;
          bx += wxx * u + wxy * v;
          by += wxy * u + wyy * v;
        }
      }
      const double det = a * c - b * b;
      // No two-directional gradient (an edge or a flat window): the system does not fix q.
      if (!(det > 1e-9 * (a + c) * (a + c))) break;
      const cv::Point2d q(cx + (c * bx - b * by) / det, cy + (a * by - b * bx) / det);
      ok = true;
      const bool settled = std::lround(q.x) == cx && std::lround(q.y) == cy;
      p = q;
      if (settled) break;
    }
    if (ok && std::abs(p.x - start.x) <= h && std::abs(p.y - start.y) <= h)
      point = cv::Point2f(static_cast<float>(p.x), static_cast<float>(p.y));
  }
}

}  // namespace reftrack
