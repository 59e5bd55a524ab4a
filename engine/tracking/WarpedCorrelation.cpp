#include "engine/tracking/WarpedCorrelation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/core/Error.hpp"
#include "engine/core/LaneDotProduct.hpp"

namespace reftrack {

WarpedCorrelation::WarpedCorrelation(const cv::Mat& frame, const cv::Mat& reference, int halfWindow)
    : frame_(frame), reference_(reference), n_(halfWindow) {
  if (frame.type() != CV_32FC1 || reference.type() != CV_32FC1)
    throw Error("WarpedCorrelation: frame and reference must be CV_32FC1 grey images");
  if (halfWindow < 1) throw Error("WarpedCorrelation: halfWindow must be >= 1");
}

WarpedCorrelation::FramePatch WarpedCorrelation::framePatch(cv::Point2f pK) const {
  FramePatch patch;
  const int cx = static_cast<int>(std::lround(pK.x)), cy = static_cast<int>(std::lround(pK.y));
  if (cx - n_ < 0 || cy - n_ < 0 || cx + n_ >= frame_.cols || cy + n_ >= frame_.rows) return patch;
  const int side = 2 * n_ + 1;
  patch.values.resize(static_cast<std::size_t>(side * side));
  double sum = 0.0;
  for (int dy = -n_, i = 0; dy <= n_; ++dy) {
    const float* row = frame_.ptr<float>(cy + dy);
    for (int dx = -n_; dx <= n_; ++dx, ++i) {
      patch.values[static_cast<std::size_t>(i)] = row[cx + dx];
      sum += row[cx + dx];
    }
  }
  const double mean = sum / static_cast<double>(patch.values.size());
  double ss = 0.0;
  for (float& v : patch.values) {
    v = static_cast<float>(v - mean);
    ss += static_cast<double>(v) * v;
  }
  // Below ~0.5 grey level of SD the window is flat: the correlation would only measure noise.
  if (ss < 0.25 * static_cast<double>(patch.values.size())) return {};
  const float inv = static_cast<float>(1.0 / std::sqrt(ss));
  for (float& v : patch.values) v *= inv;
  // Window pixel m = (cx+dx, cy+dy); its offset from the sub-pixel corner enters the warp.
  patch.centre = cv::Point2d(pK.x, pK.y);
  return patch;
}

namespace {
inline cv::Point2d apply(const cv::Matx33d& W, double x, double y) {
  const double w = W(2, 0) * x + W(2, 1) * y + W(2, 2);
  return {(W(0, 0) * x + W(0, 1) * y + W(0, 2)) / w, (W(1, 0) * x + W(1, 1) * y + W(1, 2)) / w};
}
}  // namespace

double WarpedCorrelation::score(const FramePatch& patch, const cv::Matx33d& W,
                                cv::Point2d pA) const {
  if (!patch.valid()) return -1.0;
  const int side = 2 * n_ + 1;
  const double cx = std::round(patch.centre.x), cy = std::round(patch.centre.y);
  const cv::Point2d centreW = apply(W, patch.centre.x, patch.centre.y);
  const cv::Point2d shift = pA - centreW;  // O: centre the warped window on the candidate
  thread_local std::vector<float> sampled;
  sampled.resize(static_cast<std::size_t>(side * side));
  double sum = 0.0;
  const int w = reference_.cols, h = reference_.rows;
  const std::size_t step = reference_.step1();
  const float* base = reference_.ptr<float>(0);
  for (int dy = -n_, i = 0; dy <= n_; ++dy) {
    for (int dx = -n_; dx <= n_; ++dx, ++i) {
      const cv::Point2d q = apply(W, cx + dx, cy + dy) + shift;
      const int x0 = static_cast<int>(std::floor(q.x)), y0 = static_cast<int>(std::floor(q.y));
      if (x0 < 0 || y0 < 0 || x0 + 1 >= w || y0 + 1 >= h) return -1.0;
      const float fx = static_cast<float>(q.x - x0), fy = static_cast<float>(q.y - y0);
      const float* r0 = base + static_cast<std::size_t>(y0) * step + x0;
      const float* r1 = r0 + step;
      const float v =
          (1 - fy) * ((1 - fx) * r0[0] + fx * r0[1]) + fy * ((1 - fx) * r1[0] + fx * r1[1]);
      sampled[static_cast<std::size_t>(i)] = v;
      sum += v;
    }
  }
  const double mean = sum / static_cast<double>(sampled.size());
  double ss = 0.0, dot = 0.0;
  for (std::size_t i = 0; i < sampled.size(); ++i) {
    const double d = sampled[i] - mean;
    ss += d * d;
    dot += d * patch.values[i];
  }
  if (ss < 0.25 * static_cast<double>(sampled.size())) return -1.0;
  return dot / std::sqrt(ss);
}

namespace {

// In place: subtract the mean and scale to unit norm; false when the window is flat (SD below
// ~0.5 grey level, where the correlation would only measure noise).

bool normaliseWindow(float* v, int count) {
  // Sums in eight lanes (the two running sums were ~4% of a tracked 1280x720 frame: perf, 6-DOF
  // handheld webcam sequence); the ones for the mean are a dot product with ones.
  thread_local std::vector<float> ones;
  if (static_cast<int>(ones.size()) < count) ones.assign(static_cast<std::size_t>(count), 1.0f);
  const float mean = laneDotProduct(v, ones.data(), count) / static_cast<float>(count);
  for (int i = 0; i < count; ++i) v[i] -= mean;
  const float ss = laneDotProduct(v, v, count);
  if (!(ss >= 0.25f * static_cast<float>(count))) return false;
  const float inv = 1.0f / std::sqrt(ss);
  for (int i = 0; i < count; ++i) v[i] *= inv;
  return true;
}

}  // namespace

bool sampleFrameWindow(const cv::Mat& gray8, cv::Point2d pK, int n, float* out) {
  if (gray8.type() != CV_8UC1) throw Error("sampleFrameWindow: the frame must be CV_8UC1");
  if (!std::isfinite(pK.x) || !std::isfinite(pK.y)) return false;
  const double left = pK.x - n, top = pK.y - n;
  const int x0 = static_cast<int>(std::floor(left)), y0 = static_cast<int>(std::floor(top));
  const int side = 2 * n + 1;
  if (x0 < 0 || y0 < 0 || x0 + side >= gray8.cols || y0 + side >= gray8.rows) return false;
  // One sub-pixel offset for the whole window: four fixed bilinear weights.
  const float fx = static_cast<float>(left - x0), fy = static_cast<float>(top - y0);
  const float w00 = (1 - fx) * (1 - fy), w01 = fx * (1 - fy), w10 = (1 - fx) * fy, w11 = fx * fy;
  for (int r = 0; r < side; ++r) {
    const uchar* a = gray8.ptr<uchar>(y0 + r) + x0;
    const uchar* b = gray8.ptr<uchar>(y0 + r + 1) + x0;
    float* o = out + r * side;
    for (int c = 0; c < side; ++c) o[c] = w00 * a[c] + w01 * a[c + 1] + w10 * b[c] + w11 * b[c + 1];
  }
  return normaliseWindow(out, side * side);
}

namespace {

template <typename Pixel>
bool sampleWarpedWindow(const cv::Mat& reference, const cv::Matx33d& W, cv::Point2d pK,
                        cv::Point2d pA, int n, float* out) {
  // W to first order around pK (its Jacobian J = (A - W(pK) c^T) / s for W = [A b; c^T d] and
  // s = c^T pK + d): over a (2n+1)^2 window the second-order terms are ~|c^T m / s| times the
  // window's offsets, a few thousandths of a pixel for the near-affine W = L H of tracking. The
  // window is then an affine grid: its bounds are those of its four corners and each pixel costs
  // two additions instead of two divisions (this sampler was the hottest loop of a tracked frame,
  // ~400 windows per frame; measured with callgrind on the real postcard clip: 2.3 -> 1.6 M
  // instructions per frame, the same poses there and on the simulator's handheld sequence).
  const double s = W(2, 0) * pK.x + W(2, 1) * pK.y + W(2, 2);
  const double cx = (W(0, 0) * pK.x + W(0, 1) * pK.y + W(0, 2)) / s;
  const double cy = (W(1, 0) * pK.x + W(1, 1) * pK.y + W(1, 2)) / s;
  const double j00 = (W(0, 0) - cx * W(2, 0)) / s, j01 = (W(0, 1) - cx * W(2, 1)) / s;
  const double j10 = (W(1, 0) - cy * W(2, 0)) / s, j11 = (W(1, 1) - cy * W(2, 1)) / s;
  if (!std::isfinite(j00) || !std::isfinite(j01) || !std::isfinite(j10) || !std::isfinite(j11) ||
      !std::isfinite(pA.x) || !std::isfinite(pA.y))
    return false;
  // Inside when the corners are, with a margin far above the rounding of the accumulated steps
  // below, so that no sample reads past the last column or row.
  constexpr double kMargin = 1e-6;
  const double maxX = reference.cols - 1 - kMargin, maxY = reference.rows - 1 - kMargin;
  for (const int dy : {-n, n})
    for (const int dx : {-n, n}) {
      const double qx = pA.x + j00 * dx + j01 * dy, qy = pA.y + j10 * dx + j11 * dy;
      if (!(qx >= kMargin && qy >= kMargin && qx < maxX && qy < maxY)) return false;
    }
  const std::size_t step = reference.step1();
  const Pixel* base = reference.ptr<Pixel>(0);
  for (int dy = -n, i = 0; dy <= n; ++dy) {
    double qx = pA.x - j00 * n + j01 * dy, qy = pA.y - j10 * n + j11 * dy;
    for (int dx = -n; dx <= n; ++dx, ++i, qx += j00, qy += j10) {
      const int x0 = static_cast<int>(qx), y0 = static_cast<int>(qy);
      const float fx = static_cast<float>(qx - x0), fy = static_cast<float>(qy - y0);
      const Pixel* r0 = base + static_cast<std::size_t>(y0) * step + x0;
      const Pixel* r1 = r0 + step;
      out[i] = (1 - fy) * ((1 - fx) * r0[0] + fx * r0[1]) + fy * ((1 - fx) * r1[0] + fx * r1[1]);
    }
  }
  return normaliseWindow(out, (2 * n + 1) * (2 * n + 1));
}

}  // namespace

bool sampleWarpedReferenceWindow(const cv::Mat& reference, const cv::Matx33d& W, cv::Point2d pK,
                                 cv::Point2d pA, int n, float* out) {
  // 8-bit pixels give the very same samples as their float copy (integers, the same float
  // arithmetic) from a quarter of the memory: the windows fall anywhere in the reference, and
  // at 1280x720 the float copy's cache misses were most of this function's time (perf, 6-DOF
  // handheld webcam sequence: the load of the first reference row of each sample).
  if (reference.type() == CV_8UC1) return sampleWarpedWindow<uchar>(reference, W, pK, pA, n, out);
  if (reference.type() == CV_32FC1) return sampleWarpedWindow<float>(reference, W, pK, pA, n, out);
  throw Error("sampleWarpedReferenceWindow: the reference must be CV_8UC1 or CV_32FC1");
}

void prefetchWarpedReferenceWindow(const cv::Mat& reference, const cv::Matx33d& W, cv::Point2d pK,
                                   cv::Point2d pA, int n) {
  if (reference.type() != CV_8UC1) return;
  // The window's bounding box from W's Jacobian at pK (as sampleWarpedWindow computes it).
  const double s = W(2, 0) * pK.x + W(2, 1) * pK.y + W(2, 2);
  const double cx = (W(0, 0) * pK.x + W(0, 1) * pK.y + W(0, 2)) / s;
  const double cy = (W(1, 0) * pK.x + W(1, 1) * pK.y + W(1, 2)) / s;
  const double ex =
      n * (std::abs(W(0, 0) - cx * W(2, 0)) + std::abs(W(0, 1) - cx * W(2, 1))) / std::abs(s);
  const double ey =
      n * (std::abs(W(1, 0) - cy * W(2, 0)) + std::abs(W(1, 1) - cy * W(2, 1))) / std::abs(s);
  if (!(std::isfinite(ex) && std::isfinite(ey) && std::isfinite(pA.x) && std::isfinite(pA.y)))
    return;
  const int x0 = static_cast<int>(std::clamp(pA.x - ex, 0.0, reference.cols - 1.0));
  const int x1 = static_cast<int>(std::clamp(pA.x + ex + 1, 0.0, reference.cols - 1.0));
  const int y0 = static_cast<int>(std::clamp(pA.y - ey, 0.0, reference.rows - 1.0));
  const int y1 = static_cast<int>(std::clamp(pA.y + ey + 1, 0.0, reference.rows - 1.0));
  constexpr int kLine = 64;  // bytes per cache line
  for (int y = y0; y <= y1; ++y) {
    const uchar* row = reference.ptr<uchar>(y);
    for (int x = x0 - (x0 % kLine); x <= x1; x += kLine) __builtin_prefetch(row + x);
  }
}

float windowScore(const float* a, const float* b, int count) {
  return laneDotProduct(a, b, count);  // eight partial sums: one vector register
}

}  // namespace reftrack
