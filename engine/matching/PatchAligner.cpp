#include "engine/matching/PatchAligner.hpp"

#include <cmath>
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

// Bilinear sample of an 8-bit image at (x, y), known to be inside [0, cols-1) x [0, rows-1).
inline float bilinear(const cv::Mat& image, double x, double y) {
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const float ax = static_cast<float>(x - x0), ay = static_cast<float>(y - y0);
  const uchar* p = image.ptr<uchar>(y0) + x0;
  const std::size_t step = image.step[0];
  return (1 - ay) * ((1 - ax) * p[0] + ax * p[1]) + ay * ((1 - ax) * p[step] + ax * p[step + 1]);
}

// Normalises `values` (n of them, the first `count` define the statistics when stats is given)
// to zero mean and unit variance in place; false when they are (nearly) constant.
bool normalise(float* values, int n, double mean, double sd) {
  if (!(sd > 1e-3)) return false;
  const float m = static_cast<float>(mean), inv = static_cast<float>(1.0 / sd);
  for (int i = 0; i < n; ++i) values[i] = (values[i] - m) * inv;
  return true;
}

void meanAndSd(const float* values, int n, double& mean, double& sd) {
  double s = 0, s2 = 0;
  for (int i = 0; i < n; ++i) {
    s += values[i];
    s2 += static_cast<double>(values[i]) * values[i];
  }
  mean = s / n;
  sd = std::sqrt(std::max(0.0, s2 / n - mean * mean));
}

}  // namespace

std::optional<PatchAlignment> PatchAligner::align(const cv::Mat& source, cv::Point2d sourceCentre,
                                                  const cv::Matx22d& J, const cv::Mat& target,
                                                  cv::Point2d start) const {
  if (source.type() != CV_8UC1 || target.type() != CV_8UC1)
    throw Error("patch alignment: source and target must be 8-bit grey images");
  const int n = params_.halfWindow, side = 2 * n + 1, border = side + 2, count = side * side;
  if (!std::isfinite(sourceCentre.x) || !std::isfinite(sourceCentre.y) || !std::isfinite(start.x) ||
      !std::isfinite(start.y))
    return std::nullopt;
  // The template with a one-pixel border (for its gradients): its preimage is the parallelogram
  // of its four corners' (J is linear), inside the source when they are.
  const double reach = n + 1;
  for (int c = 0; c < 4; ++c) {
    const double u = (c & 1) ? reach : -reach, v = (c & 2) ? reach : -reach;
    const double x = sourceCentre.x + J(0, 0) * u + J(0, 1) * v;
    const double y = sourceCentre.y + J(1, 0) * u + J(1, 1) * v;
    if (!(x >= 0 && y >= 0 && x < source.cols - 1 && y < source.rows - 1)) return std::nullopt;
  }
  templ_.resize(static_cast<std::size_t>(border * border));
  for (int v = 0; v < border; ++v)
    for (int u = 0; u < border; ++u) {
      const double du = u - reach, dv = v - reach;
      templ_[static_cast<std::size_t>(v * border + u)] =
          bilinear(source, sourceCentre.x + J(0, 0) * du + J(0, 1) * dv,
                   sourceCentre.y + J(1, 0) * du + J(1, 1) * dv);
    }
  // Statistics of the inner window; the whole bordered template is normalised with them.
  window_.resize(static_cast<std::size_t>(count));
  for (int v = 0; v < side; ++v)
    for (int u = 0; u < side; ++u)
      window_[static_cast<std::size_t>(v * side + u)] =
          templ_[static_cast<std::size_t>((v + 1) * border + u + 1)];
  double meanT = 0, sdT = 0;
  meanAndSd(window_.data(), count, meanT, sdT);
  if (!normalise(templ_.data(), border * border, meanT, sdT)) return std::nullopt;
  gx_.resize(static_cast<std::size_t>(count));
  gy_.resize(static_cast<std::size_t>(count));
  std::vector<float> t(static_cast<std::size_t>(count));
  double gxx = 0, gxy = 0, gyy = 0;
  for (int v = 0; v < side; ++v)
    for (int u = 0; u < side; ++u) {
      const float* p = templ_.data() + (v + 1) * border + (u + 1);
      const std::size_t k = static_cast<std::size_t>(v * side + u);
      t[k] = p[0];
      gx_[k] = 0.5f * (p[1] - p[-1]);
      gy_[k] = 0.5f * (p[border] - p[-border]);
      gxx += gx_[k] * gx_[k];
      gxy += gx_[k] * gy_[k];
      gyy += gy_[k] * gy_[k];
    }
  const double det = gxx * gyy - gxy * gxy;
  const double minEig = 0.5 * (gxx + gyy) - std::sqrt(0.25 * (gxx - gyy) * (gxx - gyy) + gxy * gxy);
  if (!(det > 0) || !(minEig / count >= params_.minGradientEigenvalue)) return std::nullopt;

  // The target window at start + d, normalised; false when it leaves the target or is flat.
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
        w[u] = w00 * r0[u] + w01 * r0[u + 1] + w10 * r1[u] + w11 * r1[u + 1];
    }
    double mean = 0, sd = 0;
    meanAndSd(window_.data(), count, mean, sd);
    return normalise(window_.data(), count, mean, sd);
  };
  double dx = 0, dy = 0;
  const double eps2 = params_.epsilonPx * params_.epsilonPx;
  const double maxShift2 = params_.maxShiftPx * params_.maxShiftPx;
  for (int it = 0; it < params_.maxIterations; ++it) {
    if (!sample(dx, dy)) return std::nullopt;
    double bx = 0, by = 0;
    for (int k = 0; k < count; ++k) {
      const double e = t[static_cast<std::size_t>(k)] - window_[static_cast<std::size_t>(k)];
      bx += gx_[static_cast<std::size_t>(k)] * e;
      by += gy_[static_cast<std::size_t>(k)] * e;
    }
    const double ddx = (gyy * bx - gxy * by) / det, ddy = (gxx * by - gxy * bx) / det;
    dx += ddx;
    dy += ddy;
    if (!(dx * dx + dy * dy <= maxShift2)) return std::nullopt;
    if (ddx * ddx + ddy * ddy < eps2) break;
  }
  if (!sample(dx, dy)) return std::nullopt;
  double dot = 0, sse = 0;
  for (int k = 0; k < count; ++k) {
    const double a = t[static_cast<std::size_t>(k)], b = window_[static_cast<std::size_t>(k)];
    dot += a * b;
    sse += (a - b) * (a - b);
  }
  PatchAlignment out;
  out.position = cv::Point2f(static_cast<float>(start.x + dx), static_cast<float>(start.y + dy));
  out.score = dot / count;
  if (out.score < params_.minScore) return std::nullopt;
  // cov(d) = s^2 (G^T G)^-1 with s^2 = SSE / (N - 2); trace of the inverse = (gxx + gyy) / det.
  const double s2 = sse / (count - 2);
  out.sigmaPx = std::sqrt(0.5 * s2 * (gxx + gyy) / det);
  return out;
}

}  // namespace reftrack
