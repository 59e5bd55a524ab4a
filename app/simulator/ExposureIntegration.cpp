#include "app/simulator/ExposureIntegration.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

// Integral of the unit tent max(0, 1 - |v|) from -infinity to u.
double tentIntegral(double u) {
  if (u <= -1.0) return 0.0;
  if (u <= 0.0) return 0.5 * (u + 1.0) * (u + 1.0);
  if (u <= 1.0) return 1.0 - 0.5 * (1.0 - u) * (1.0 - u);
  return 1.0;
}

}  // namespace

double RowExposureTiming::rowCentre(double frameTime, int row) const {
  return frameTime + (row - 0.5 * (rows - 1)) * lineDelayFrames;
}

double RowExposureTiming::span() const { return exposureFrames + (rows - 1) * lineDelayFrames; }

int RowExposureTiming::automaticSamples() const {
  if (span() <= 0.0) return 1;
  return std::max(3, static_cast<int>(std::ceil(span() * 8.0)) + 1);
}

void RowExposureTiming::check() const {
  if (rows < 1) throw Error("exposure timing: rows must be at least 1");
  if (!(std::isfinite(exposureFrames) && exposureFrames >= 0.0))
    throw Error("exposure timing: exposure must be a non-negative number of frames");
  if (!(std::isfinite(lineDelayFrames) && lineDelayFrames >= 0.0))
    throw Error("exposure timing: line delay must be a non-negative number of frames");
}

cv::Mat integrateExposure(const std::function<cv::Mat(double frameTime)>& renderAt,
                          double frameTime, const RowExposureTiming& timing, int samples) {
  timing.check();
  if (samples < 1) throw Error("integrateExposure: samples must be at least 1");
  const auto asFloat = [&](double t) {
    cv::Mat image = renderAt(t), value;
    if (image.rows != timing.rows || image.channels() != 3)
      throw Error("integrateExposure: a render has " + std::to_string(image.rows) +
                  " rows or not 3 channels; expected " + std::to_string(timing.rows));
    image.convertTo(value, CV_32FC3);
    return value;
  };
  const double span = timing.span();
  if (samples == 1 || span <= 0.0) return asFloat(frameTime);
  const double first = frameTime - 0.5 * span, step = span / (samples - 1);
  cv::Mat out;
  std::vector<double> weights(static_cast<std::size_t>(timing.rows));
  for (int j = 0; j < samples; ++j) {
    const double tj = first + j * step;
    // Weight of render j in each row: the mean over the row's window of its interpolation tent.
    bool used = false;
    for (int r = 0; r < timing.rows; ++r) {
      const double c = timing.rowCentre(frameTime, r);
      double w;
      if (timing.exposureFrames > 0.0) {
        const double a = c - 0.5 * timing.exposureFrames, b = c + 0.5 * timing.exposureFrames;
        w = step * (tentIntegral((b - tj) / step) - tentIntegral((a - tj) / step)) /
            timing.exposureFrames;
      } else {
        w = std::max(0.0, 1.0 - std::abs(c - tj) / step);
      }
      weights[static_cast<std::size_t>(r)] = w;
      used = used || w > 1e-12;
    }
    if (!used) continue;
    const cv::Mat render = asFloat(tj);
    if (out.empty()) out = cv::Mat::zeros(render.size(), CV_32FC3);
    for (int r = 0; r < timing.rows; ++r) {
      const double w = weights[static_cast<std::size_t>(r)];
      if (w > 1e-12) cv::scaleAdd(render.row(r), w, out.row(r), out.row(r));
    }
  }
  return out;
}

}  // namespace reftrack::app
