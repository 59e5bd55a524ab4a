#include "engine/tracking/WarpedCorrelation.hpp"

#include <cmath>

#include "engine/core/Error.hpp"

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

}  // namespace reftrack
