#include "engine/homography/WindowAlignment.hpp"

#include <cmath>

#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

// Bilinear sample of an 8-bit image at (x, y); false outside [0, cols - 1) x [0, rows - 1).
inline bool sample(const cv::Mat& image, double x, double y, float& out) {
  if (!(x >= 0 && y >= 0 && x < image.cols - 1 && y < image.rows - 1)) return false;
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const float fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
  const uchar* r0 = image.ptr<uchar>(y0) + x0;
  const uchar* r1 = image.ptr<uchar>(y0 + 1) + x0;
  out = (1 - fy) * ((1 - fx) * r0[0] + fx * r0[1]) + fy * ((1 - fx) * r1[0] + fx * r1[1]);
  return true;
}

}  // namespace

WindowAlignmentResult alignWindows(const cv::Mat& reference, const cv::Mat& frame,
                                   const cv::Matx33d& H, const std::vector<cv::Point2f>& predicted,
                                   int half, int maxIterations, double epsilonPx) {
  if (reference.type() != CV_8UC1 || frame.type() != CV_8UC1)
    throw Error("window alignment: the reference and the frame must be 8-bit grey");
  if (half < 1) throw Error("window alignment: half must be >= 1");
  const cv::Matx33d Hinv = H.inv();
  const int side = 2 * half + 1, border = side + 2;
  const int count = side * side;
  WindowAlignmentResult out;
  out.found = predicted;
  out.status.assign(predicted.size(), 0);
  std::vector<float> templ(static_cast<std::size_t>(border * border));
  std::vector<float> window(static_cast<std::size_t>(count)), gx(window.size()), gy(window.size());
  const double eps2 = epsilonPx * epsilonPx;
  for (std::size_t i = 0; i < predicted.size(); ++i) {
    const cv::Point2d q(predicted[i]);
    // The template: the reference through H^-1 at q + u, u over the window and a 1-pixel border.
    bool inside = true;
    for (int v = 0; v < border && inside; ++v)
      for (int u = 0; u < border; ++u) {
        const double fx = q.x + (u - half - 1), fy = q.y + (v - half - 1);
        const double w = Hinv(2, 0) * fx + Hinv(2, 1) * fy + Hinv(2, 2);
        const double rx = (Hinv(0, 0) * fx + Hinv(0, 1) * fy + Hinv(0, 2)) / w;
        const double ry = (Hinv(1, 0) * fx + Hinv(1, 1) * fy + Hinv(1, 2)) / w;
        if (!(w > 0) ||
            !sample(reference, rx, ry, templ[static_cast<std::size_t>(v * border + u)])) {
          inside = false;
          break;
        }
      }
    if (!inside) continue;
    // Central-difference gradients and the 2x2 gradient matrix G.
    double gxx = 0, gxy = 0, gyy = 0;
    for (int v = 0; v < side; ++v)
      for (int u = 0; u < side; ++u) {
        const float* t = templ.data() + (v + 1) * border + (u + 1);
        const std::size_t k = static_cast<std::size_t>(v * side + u);
        window[k] = t[0];
        gx[k] = 0.5f * (t[1] - t[-1]);
        gy[k] = 0.5f * (t[border] - t[-border]);
        gxx += gx[k] * gx[k];
        gxy += gx[k] * gy[k];
        gyy += gy[k] * gy[k];
      }
    const double det = gxx * gyy - gxy * gxy;
    const double minEig =
        0.5 * (gxx + gyy) - std::sqrt(0.25 * (gxx - gyy) * (gxx - gyy) + gxy * gxy);
    if (!(minEig / count >= 1e-2) || !(det > 0)) continue;
    // Lucas-Kanade: the frame window at q + d (one set of bilinear weights for the whole window).
    // As cv::calcOpticalFlowPyrLK, a point still moving after maxIterations keeps its last d.
    double dx = 0, dy = 0;
    bool ok = true;
    for (int it = 0; it < maxIterations; ++it) {
      const double cx = q.x + dx - half, cy = q.y + dy - half;  // the window's first pixel
      if (!(cx >= 0 && cy >= 0 && cx + side < frame.cols - 1 && cy + side < frame.rows - 1)) {
        ok = false;
        break;
      }
      const int x0 = static_cast<int>(cx), y0 = static_cast<int>(cy);
      const float ax = static_cast<float>(cx - x0), ay = static_cast<float>(cy - y0);
      const float w00 = (1 - ax) * (1 - ay), w01 = ax * (1 - ay), w10 = (1 - ax) * ay,
                  w11 = ax * ay;
      double bx = 0, by = 0;
      for (int v = 0; v < side; ++v) {
        const uchar* r0 = frame.ptr<uchar>(y0 + v) + x0;
        const uchar* r1 = frame.ptr<uchar>(y0 + v + 1) + x0;
        const std::size_t row = static_cast<std::size_t>(v * side);
        float sx = 0, sy = 0;
        for (int u = 0; u < side; ++u) {
          const float j = w00 * r0[u] + w01 * r0[u + 1] + w10 * r1[u] + w11 * r1[u + 1];
          const float e = window[row + static_cast<std::size_t>(u)] - j;
          sx += e * gx[row + static_cast<std::size_t>(u)];
          sy += e * gy[row + static_cast<std::size_t>(u)];
        }
        bx += sx;
        by += sy;
      }
      const double ddx = (gyy * bx - gxy * by) / det, ddy = (gxx * by - gxy * bx) / det;
      dx += ddx;
      dy += ddy;
      if (!(std::abs(dx) <= half && std::abs(dy) <= half)) {
        ok = false;
        break;
      }
      if (ddx * ddx + ddy * ddy < eps2) break;
    }
    if (!ok) continue;
    out.status[i] = 1;
    out.found[i] = cv::Point2f(static_cast<float>(q.x + dx), static_cast<float>(q.y + dy));
  }
  return out;
}

}  // namespace reftrack
