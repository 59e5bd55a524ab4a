#include "engine/matching/PatchAligner.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core/hal/intrin.hpp>
#include <string>

#include "engine/core/Error.hpp"

namespace reftrack {

void PatchAlignerParams::check() const {
  const auto bad = [](const std::string& field, const std::string& rule) {
    throw Error("patch alignment: " + field + " " + rule);
  };
  if (halfWindow < 1 || halfWindow > 32) bad("half_window", "must be in [1, 32]");
  if (maxIterations < 1 || maxIterations > 100) bad("max_iterations", "must be in [1, 100]");
  if (!(epsilonPx > 0) || !std::isfinite(epsilonPx)) bad("epsilon_px", "must be > 0");
  if (!(maxShiftPx > 0) || !std::isfinite(maxShiftPx)) bad("max_shift_px", "must be > 0");
  if (!(minGradientEigenvalue >= 0) || !std::isfinite(minGradientEigenvalue))
    bad("min_gradient_eigenvalue", "must be >= 0");
  if (!(minScore >= -1 && minScore <= 1)) bad("min_score", "must be in [-1, 1]");
}

PatchAligner::PatchAligner(PatchAlignerParams params) : params_(params) { params_.check(); }

namespace {

// The windows' arrays are padded with zeros to a multiple of the SIMD width.
constexpr int kLanes = 4;
constexpr float kOffset = 128.0f;  // target samples are stored minus this (smaller float sums)

// Sums over n (a multiple of kLanes) floats: of w, w^2, gx w, gy w and t w.
struct WindowSums {
  double w = 0, ww = 0, gxw = 0, gyw = 0, tw = 0;
};

WindowSums windowSums(const float* w, const float* gx, const float* gy, const float* t, int n) {
  WindowSums out;
#if CV_SIMD128
  cv::v_float32x4 sw = cv::v_setzero_f32(), sww = sw, sgx = sw, sgy = sw, stw = sw;
  for (int k = 0; k < n; k += kLanes) {
    const cv::v_float32x4 a = cv::v_load(w + k);
    sw += a;
    sww = cv::v_fma(a, a, sww);
    sgx = cv::v_fma(cv::v_load(gx + k), a, sgx);
    sgy = cv::v_fma(cv::v_load(gy + k), a, sgy);
    stw = cv::v_fma(cv::v_load(t + k), a, stw);
  }
  out.w = cv::v_reduce_sum(sw);
  out.ww = cv::v_reduce_sum(sww);
  out.gxw = cv::v_reduce_sum(sgx);
  out.gyw = cv::v_reduce_sum(sgy);
  out.tw = cv::v_reduce_sum(stw);
#else
  float sw[kLanes] = {}, sww[kLanes] = {}, sgx[kLanes] = {}, sgy[kLanes] = {}, stw[kLanes] = {};
  for (int k = 0; k < n; k += kLanes)
    for (int l = 0; l < kLanes; ++l) {
      const float a = w[k + l];
      sw[l] += a;
      sww[l] += a * a;
      sgx[l] += gx[k + l] * a;
      sgy[l] += gy[k + l] * a;
      stw[l] += t[k + l] * a;
    }
  for (int l = 0; l < kLanes; ++l) {
    out.w += sw[l];
    out.ww += sww[l];
    out.gxw += sgx[l];
    out.gyw += sgy[l];
    out.tw += stw[l];
  }
#endif
  return out;
}

}  // namespace

// The iterations work on sums: with the target window w normalised as (w - m) / s, the residual
// projections sum_k g_k (t_k - w'_k) = sum g t - (sum g w - m sum g) / s, and the correlation
// sum t w' = (sum t w - m sum t) / s, so each step samples the window once and takes five dot
// products of it (one SIMD pass) instead of normalising it and summing the residuals (four
// passes): the keypoint stage 0.51 -> 0.37 ms per desk frame (research README, "The keypoint
// layer's cost").
std::optional<PatchAlignment> PatchAligner::align(const cv::Mat& source, cv::Point2d sourceCentre,
                                                  const cv::Matx22d& J, const cv::Mat& target,
                                                  cv::Point2d start) const {
  if (source.type() != CV_8UC1 || target.type() != CV_8UC1)
    throw Error("patch alignment: source and target must be 8-bit grey images");
  const int n = params_.halfWindow, side = 2 * n + 1, border = side + 2, count = side * side;
  const int paddedCount = (count + kLanes - 1) / kLanes * kLanes;
  if (!std::isfinite(sourceCentre.x) || !std::isfinite(sourceCentre.y) || !std::isfinite(start.x) ||
      !std::isfinite(start.y))
    return std::nullopt;
  // The template with a one-pixel border (for its gradients): its preimage is the parallelogram
  // of its four corners' (J is linear), inside the source when they are (with a margin for the
  // rounding of the stepped positions below).
  const double reach = n + 1;
  for (int c = 0; c < 4; ++c) {
    const double u = (c & 1) ? reach : -reach, v = (c & 2) ? reach : -reach;
    const double x = sourceCentre.x + J(0, 0) * u + J(0, 1) * v;
    const double y = sourceCentre.y + J(1, 0) * u + J(1, 1) * v;
    if (!(x >= 1e-6 && y >= 1e-6 && x < source.cols - 1 - 1e-6 && y < source.rows - 1 - 1e-6))
      return std::nullopt;
  }
  // Sampled row by row, each row's positions stepped by J's first column; the bilinear weights
  // in the form a + ax (b - a) + ay (c - a) + ax ay (d - c - b + a) (integer differences).
  templ_.resize(static_cast<std::size_t>(border * border));
  const uchar* image = source.data;
  const std::size_t step = source.step[0];
  for (int v = 0; v < border; ++v) {
    const double dv = v - reach;
    double x = sourceCentre.x - J(0, 0) * reach + J(0, 1) * dv;
    double y = sourceCentre.y - J(1, 0) * reach + J(1, 1) * dv;
    float* row = templ_.data() + v * border;
    for (int u = 0; u < border; ++u, x += J(0, 0), y += J(1, 0)) {
      const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);  // x, y >= 0: the floor
      const float ax = static_cast<float>(x - x0), ay = static_cast<float>(y - y0);
      const uchar* q = image + static_cast<std::size_t>(y0) * step + x0;
      const int a = q[0], b = q[1], c = q[step], d = q[step + 1];
      row[u] = static_cast<float>(a) + ax * static_cast<float>(b - a) +
               ay * (static_cast<float>(c - a) + ax * static_cast<float>(d - c - b + a));
    }
  }
  // Statistics of the inner window; the template and its gradients are normalised with them.
  double s = 0, s2 = 0;
  for (int v = 1; v <= side; ++v)
    for (int u = 1; u <= side; ++u) {
      const double a = templ_[static_cast<std::size_t>(v * border + u)];
      s += a;
      s2 += a * a;
    }
  const double meanT = s / count, sdT = std::sqrt(std::max(0.0, s2 / count - meanT * meanT));
  if (!(sdT > 1e-3)) return std::nullopt;
  const float mT = static_cast<float>(meanT), invT = static_cast<float>(1.0 / sdT);
  // The template t and its gradients over the inner window, zero-padded.
  t_.assign(static_cast<std::size_t>(paddedCount), 0.0f);
  gx_.assign(static_cast<std::size_t>(paddedCount), 0.0f);
  gy_.assign(static_cast<std::size_t>(paddedCount), 0.0f);
  double gxx = 0, gxy = 0, gyy = 0, sumGx = 0, sumGy = 0, sumGxT = 0, sumGyT = 0, sumT = 0,
         sumTT = 0;
  const float halfInv = 0.5f * invT;
  for (int v = 0; v < side; ++v)
    for (int u = 0; u < side; ++u) {
      const float* p = templ_.data() + (v + 1) * border + (u + 1);
      const std::size_t k = static_cast<std::size_t>(v * side + u);
      const float t = (p[0] - mT) * invT;
      const float gx = halfInv * (p[1] - p[-1]), gy = halfInv * (p[border] - p[-border]);
      t_[k] = t;
      gx_[k] = gx;
      gy_[k] = gy;
      gxx += gx * gx;
      gxy += gx * gy;
      gyy += gy * gy;
      sumGx += gx;
      sumGy += gy;
      sumGxT += gx * t;
      sumGyT += gy * t;
      sumT += t;
      sumTT += t * t;
    }
  const double det = gxx * gyy - gxy * gxy;
  const double minEig = 0.5 * (gxx + gyy) - std::sqrt(0.25 * (gxx - gyy) * (gxx - gyy) + gxy * gxy);
  if (!(det > 0) || !(minEig / count >= params_.minGradientEigenvalue)) return std::nullopt;

  // The target window at start + d (minus kOffset, zero-padded) and its sums with the template;
  // false when it leaves the target or is flat. mean / sd: of the window's samples.
  window_.assign(static_cast<std::size_t>(paddedCount), 0.0f);
  WindowSums sums;
  double mean = 0, sd = 0;
  const auto sample = [&](double dx, double dy) {
    const double cx = start.x + dx - n, cy = start.y + dy - n;
    if (!(cx >= 0 && cy >= 0 && cx + side < target.cols - 1 && cy + side < target.rows - 1))
      return false;
    const int x0 = static_cast<int>(cx), y0 = static_cast<int>(cy);
    const float ax = static_cast<float>(cx - x0), ay = static_cast<float>(cy - y0);
    const float w00 = (1 - ax) * (1 - ay), w01 = ax * (1 - ay), w10 = (1 - ax) * ay, w11 = ax * ay;
    for (int v = 0; v < side; ++v) {
      const uchar* r0 = target.ptr<uchar>(y0 + v) + x0;
      const uchar* r1 = target.ptr<uchar>(y0 + v + 1) + x0;
      float* w = window_.data() + v * side;
      for (int u = 0; u < side; ++u)
        w[u] = w00 * r0[u] + w01 * r0[u + 1] + w10 * r1[u] + w11 * r1[u + 1] - kOffset;
    }
    sums = windowSums(window_.data(), gx_.data(), gy_.data(), t_.data(), paddedCount);
    mean = sums.w / count;
    sd = std::sqrt(std::max(0.0, sums.ww / count - mean * mean));
    return sd > 1e-3;
  };
  double dx = 0, dy = 0;
  const double eps2 = params_.epsilonPx * params_.epsilonPx;
  const double maxShift2 = params_.maxShiftPx * params_.maxShiftPx;
  for (int it = 0; it < params_.maxIterations; ++it) {
    if (!sample(dx, dy)) return std::nullopt;
    // sum_k g_k (t_k - (w_k - mean) / sd)
    const double bx = sumGxT - (sums.gxw - mean * sumGx) / sd;
    const double by = sumGyT - (sums.gyw - mean * sumGy) / sd;
    const double ddx = (gyy * bx - gxy * by) / det, ddy = (gxx * by - gxy * bx) / det;
    dx += ddx;
    dy += ddy;
    if (!(dx * dx + dy * dy <= maxShift2)) return std::nullopt;
    if (ddx * ddx + ddy * ddy < eps2) break;
  }
  if (!sample(dx, dy)) return std::nullopt;
  // sum t w' and sum (t - w')^2 = sum t^2 - 2 sum t w' + sum w'^2 (the last is count).
  const double dot = (sums.tw - mean * sumT) / sd;
  const double sse = std::max(0.0, sumTT - 2.0 * dot + count);
  PatchAlignment out;
  out.position = cv::Point2f(static_cast<float>(start.x + dx), static_cast<float>(start.y + dy));
  out.score = dot / count;
  if (out.score < params_.minScore) return std::nullopt;
  // cov(d) = s^2 (G^T G)^-1 with s^2 = SSE / (N - 2); trace of the inverse = (gxx + gyy) / det.
  const double s2n = sse / (count - 2);
  out.sigmaPx = std::sqrt(0.5 * s2n * (gxx + gyy) / det);
  return out;
}

}  // namespace reftrack
