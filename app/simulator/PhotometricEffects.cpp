#include "app/simulator/PhotometricEffects.hpp"

#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "app/simulator/SensorNoise.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {
constexpr std::uint64_t kGainStream = 0x4741494E53544550ull;
}

cv::Mat defocusKernel(double radiusPx) {
  if (!(std::isfinite(radiusPx) && radiusPx > 0.0))
    throw Error("defocus: the disc radius must be a positive number of pixels");
  const int half = static_cast<int>(std::ceil(radiusPx));
  const int side = 2 * half + 1;
  constexpr int kSub = 8;
  cv::Mat kernel(side, side, CV_32F);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      int inside = 0;
      for (int sy = 0; sy < kSub; ++sy)
        for (int sx = 0; sx < kSub; ++sx) {
          const double dx = x - half - 0.5 + (sx + 0.5) / kSub;
          const double dy = y - half - 0.5 + (sy + 0.5) / kSub;
          if (dx * dx + dy * dy <= radiusPx * radiusPx) ++inside;
        }
      kernel.at<float>(y, x) = static_cast<float>(inside);
    }
  return kernel / cv::sum(kernel)[0];
}

cv::Mat defocus(const cv::Mat& image, double radiusPx) {
  if (radiusPx == 0.0) return image;
  cv::Mat out;
  cv::filter2D(image, out, -1, defocusKernel(radiusPx), cv::Point(-1, -1), 0.0, cv::BORDER_REFLECT);
  return out;
}

cv::Mat vignettingGain(cv::Size size, double strength) {
  if (!(std::isfinite(strength) && strength >= 0.0 && strength <= 1.0))
    throw Error("vignetting: strength must be in [0, 1]");
  const double cx = 0.5 * (size.width - 1), cy = 0.5 * (size.height - 1);
  const double corner2 = std::max(1e-12, cx * cx + cy * cy);
  cv::Mat gain(size, CV_32F);
  for (int y = 0; y < size.height; ++y) {
    float* row = gain.ptr<float>(y);
    for (int x = 0; x < size.width; ++x)
      row[x] = static_cast<float>(1.0 -
                                  strength * ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / corner2);
  }
  return gain;
}

double autoExposureGain(std::uint64_t seed, double seconds, double step, double stepSeconds) {
  if (!(stepSeconds > 0.0)) throw Error("auto-exposure: step interval must be positive");
  const double level = std::floor(seconds / stepSeconds);
  if (step == 0.0 || level <= 0.0) return 1.0;
  const std::uint64_t bits = mixSeed(mixSeed(seed, kGainStream), static_cast<std::uint64_t>(level));
  const double u = static_cast<double>(bits >> 11) / 9007199254740992.0;  // [0, 1)
  return 1.0 + step * (2.0 * u - 1.0);
}

cv::Mat flickerRowGain(const RowExposureTiming& timing, double frameTime, double fps,
                       double amplitude, double hz) {
  timing.check();
  const double w = 2.0 * std::numbers::pi * hz;
  cv::Mat gain(timing.rows, 1, CV_32F);
  for (int r = 0; r < timing.rows; ++r) {
    const double c = timing.rowCentre(frameTime, r) / fps;
    const double e = timing.exposureFrames / fps;
    // Mean of cos(w t) over [c - e/2, c + e/2]: cos(w c) sinc(w e / 2).
    const double x = 0.5 * w * e;
    const double sinc = x > 1e-9 ? std::sin(x) / x : 1.0;
    gain.at<float>(r) = static_cast<float>(1.0 + amplitude * std::cos(w * c) * sinc);
  }
  return gain;
}

cv::Mat addPoissonGaussianNoise(const cv::Mat& image, std::uint64_t seed, double conversionGain,
                                double readNoise) {
  if (image.empty() || image.type() != CV_32FC3)
    throw Error("addPoissonGaussianNoise: expected a CV_32FC3 image");
  if (!(conversionGain >= 0.0 && readNoise >= 0.0))
    throw Error("addPoissonGaussianNoise: gain and read noise must be non-negative");
  cv::Mat positive, variance, sd;
  cv::max(image, cv::Scalar::all(0.0), positive);
  positive.convertTo(variance, CV_32FC3, conversionGain, readNoise * readNoise);
  cv::sqrt(variance, sd);
  cv::Mat noise(image.size(), CV_32FC3);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 1.0);
  cv::Mat value = image + noise.mul(sd), out;
  value.convertTo(out, CV_8UC3);  // rounds to nearest and saturates
  return out;
}

}  // namespace reftrack::app
