#include "engine/matching/NccCorrelation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

void requireGray(const cv::Mat& gray) {
  if (gray.empty() || gray.type() != CV_8UC1)
    throw Error("NCC windows need a non-empty 8-bit grey image");
}

}  // namespace

NccPatches::NccPatches(int halfWindow)
    : half_(halfWindow),
      area_((2 * halfWindow + 1) * (2 * halfWindow + 1)),
      stride_((area_ + kLanes - 1) / kLanes * kLanes) {
  if (halfWindow < 1) throw Error("NCC half window must be at least 1");
}

void NccPatches::normaliseLast(int i) {
  float* p = data_.data() + static_cast<size_t>(i) * stride_;
  double sum = 0;
  for (int k = 0; k < area_; ++k) sum += p[k];
  const float mean = static_cast<float>(sum / area_);
  double sq = 0;
  for (int k = 0; k < area_; ++k) {
    p[k] -= mean;
    sq += static_cast<double>(p[k]) * p[k];
  }
  // A flat window (sd below 1/100 grey level) has no defined correlation.
  if (sq < 1e-4 * area_) {
    valid_[static_cast<size_t>(i)] = 0;
    return;
  }
  const float inv = static_cast<float>(1.0 / std::sqrt(sq));
  for (int k = 0; k < area_; ++k) p[k] *= inv;
}

NccPatches NccPatches::square(const cv::Mat& gray, const std::vector<cv::Point2f>& centres,
                              int halfWindow) {
  requireGray(gray);
  NccPatches out(halfWindow);
  const int n = static_cast<int>(centres.size());
  out.data_.assign(static_cast<size_t>(n) * out.stride_, 0.0f);
  out.valid_.assign(static_cast<size_t>(n), 1);
  const int h = halfWindow;
  for (int i = 0; i < n; ++i) {
    const int cx = static_cast<int>(std::lround(centres[i].x));
    const int cy = static_cast<int>(std::lround(centres[i].y));
    if (!(cx - h >= 0 && cy - h >= 0 && cx + h < gray.cols && cy + h < gray.rows)) {
      out.valid_[static_cast<size_t>(i)] = 0;
      continue;
    }
    float* p = out.data_.data() + static_cast<size_t>(i) * out.stride_;
    for (int y = cy - h; y <= cy + h; ++y) {
      const uchar* row = gray.ptr<uchar>(y);
      for (int x = cx - h; x <= cx + h; ++x) *p++ = row[x];
    }
    out.normaliseLast(i);
  }
  return out;
}

NccPatches NccPatches::warped(const cv::Mat& gray, const std::vector<cv::Point2f>& centres,
                              const std::vector<cv::Matx22f>& maps, int halfWindow) {
  requireGray(gray);
  if (maps.size() != centres.size())
    throw Error("warped NCC windows: one local map per centre is required");
  NccPatches out(halfWindow);
  const int n = static_cast<int>(centres.size());
  out.data_.assign(static_cast<size_t>(n) * out.stride_, 0.0f);
  out.valid_.assign(static_cast<size_t>(n), 1);
  const int h = halfWindow, side = 2 * h + 1, cells = side * side;
  const float maxX = static_cast<float>(gray.cols - 1), maxY = static_cast<float>(gray.rows - 1);
  // The window's offsets (u, v) and per-pixel scratch: the affine map's image of the window is a
  // parallelogram, inside the image when its four corners are, so the pixels need no bounds test
  // and the coordinate and interpolation loops vectorise (the per-pixel scalar loop was ~8% of a
  // tracked 1280x720 homography frame: callgrind, bench-homography frames). The same samples.
  thread_local std::vector<float> du, dv, xs, ys, p00, p01, p10, p11;
  thread_local std::vector<int> offset;
  for (auto* v : {&du, &dv, &xs, &ys, &p00, &p01, &p10, &p11})
    v->resize(static_cast<size_t>(cells));
  offset.resize(static_cast<size_t>(cells));
  for (int k = 0; k < cells; ++k) {
    du[static_cast<size_t>(k)] = static_cast<float>(k % side - h);
    dv[static_cast<size_t>(k)] = static_cast<float>(k / side - h);
  }
  const int step = static_cast<int>(gray.step[0]);
  for (int i = 0; i < n; ++i) {
    const cv::Matx22f& A = maps[static_cast<size_t>(i)];
    const cv::Point2f c = centres[static_cast<size_t>(i)];
    float* p = out.data_.data() + static_cast<size_t>(i) * out.stride_;
    bool inside = std::isfinite(c.x) && std::isfinite(c.y);
    for (int k = 0; k < 4 && inside; ++k) {
      const float u = static_cast<float>((k & 1) ? h : -h),
                  v = static_cast<float>((k & 2) ? h : -h);
      const float x = c.x + A(0, 0) * u + A(0, 1) * v;
      const float y = c.y + A(1, 0) * u + A(1, 1) * v;
      inside = x >= 0 && y >= 0 && x < maxX && y < maxY;
    }
    if (!inside) {
      out.valid_[static_cast<size_t>(i)] = 0;
      continue;
    }
    const float a00 = A(0, 0), a01 = A(0, 1), a10 = A(1, 0), a11 = A(1, 1);
    // Clamped just inside: rounding may put an edge pixel a hair past a corner's bound.
    const float lastX = std::nextafter(maxX, 0.0f), lastY = std::nextafter(maxY, 0.0f);
    for (int k = 0; k < cells; ++k) {
      xs[static_cast<size_t>(k)] = std::min(
          std::max(c.x + a00 * du[static_cast<size_t>(k)] + a01 * dv[static_cast<size_t>(k)], 0.0f),
          lastX);
      ys[static_cast<size_t>(k)] = std::min(
          std::max(c.y + a10 * du[static_cast<size_t>(k)] + a11 * dv[static_cast<size_t>(k)], 0.0f),
          lastY);
    }
    for (int k = 0; k < cells; ++k) {
      const int x0 = static_cast<int>(xs[static_cast<size_t>(k)]);
      const int y0 = static_cast<int>(ys[static_cast<size_t>(k)]);
      xs[static_cast<size_t>(k)] -= static_cast<float>(x0);
      ys[static_cast<size_t>(k)] -= static_cast<float>(y0);
      offset[static_cast<size_t>(k)] = y0 * step + x0;
    }
    for (int k = 0; k < cells; ++k) {
      const uchar* r0 = gray.data + offset[static_cast<size_t>(k)];
      p00[static_cast<size_t>(k)] = r0[0];
      p01[static_cast<size_t>(k)] = r0[1];
      p10[static_cast<size_t>(k)] = r0[step];
      p11[static_cast<size_t>(k)] = r0[step + 1];
    }
    for (int k = 0; k < cells; ++k) {
      const size_t j = static_cast<size_t>(k);
      const float fx = xs[j], fy = ys[j];
      p[k] = (1 - fy) * ((1 - fx) * p00[j] + fx * p01[j]) + fy * ((1 - fx) * p10[j] + fx * p11[j]);
    }
    out.normaliseLast(i);
  }
  return out;
}

float NccPatches::score(int i, const NccPatches& other, int j) const {
  if (other.area_ != area_) throw Error("NCC windows of different sizes cannot be compared");
  if (!valid(i) || !other.valid(j)) return -1.0f;
  const float* a = patch(i);
  const float* b = other.patch(j);
  // kLanes independent partial sums over the zero-padded stride: the compiler maps them onto
  // one SIMD register (a single running sum would serialise on the float additions).
  float lanes[kLanes] = {};
  for (int k = 0; k < stride_; k += kLanes)
    for (int l = 0; l < kLanes; ++l) lanes[l] += a[k + l] * b[k + l];
  float s = 0.0f;
  for (int l = 0; l < kLanes; ++l) s += lanes[l];
  return s;
}

double nccAt(const cv::Mat& gray1, cv::Point c1, const cv::Mat& gray2, cv::Point c2,
             int halfWindow) {
  requireGray(gray1);
  requireGray(gray2);
  const int h = halfWindow;
  const cv::Rect r1(c1.x - h, c1.y - h, 2 * h + 1, 2 * h + 1);
  const cv::Rect r2(c2.x - h, c2.y - h, 2 * h + 1, 2 * h + 1);
  if ((r1 & cv::Rect(0, 0, gray1.cols, gray1.rows)) != r1 ||
      (r2 & cv::Rect(0, 0, gray2.cols, gray2.rows)) != r2)
    return -1.0;
  cv::Scalar m1, s1, m2, s2;
  cv::meanStdDev(gray1(r1), m1, s1);
  cv::meanStdDev(gray2(r2), m2, s2);
  if (s1[0] <= 0.01 || s2[0] <= 0.01) return -1.0;
  double sum = 0;
  for (int y = 0; y < r1.height; ++y)
    for (int x = 0; x < r1.width; ++x)
      sum += (gray1(r1).at<uchar>(y, x) - m1[0]) * (gray2(r2).at<uchar>(y, x) - m2[0]);
  return sum / (static_cast<double>(r1.area()) * s1[0] * s2[0]);
}

}  // namespace reftrack
