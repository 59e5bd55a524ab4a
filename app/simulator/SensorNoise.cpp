#include "app/simulator/SensorNoise.hpp"

#include <cmath>

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {
std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
}  // namespace

std::uint64_t mixSeed(std::uint64_t a, std::uint64_t b) {
  return splitMix64(splitMix64(a) ^ (b + 0x632BE59BD9B4E019ull));
}

cv::Mat addSensorNoise(const cv::Mat& image, std::uint64_t seed, double sigma) {
  if (image.empty() || image.channels() != 3 || (image.depth() != CV_8U && image.depth() != CV_32F))
    throw Error("addSensorNoise: expected a CV_8UC3 or CV_32FC3 image");
  if (!(std::isfinite(sigma) && sigma >= 0.0))
    throw Error("addSensorNoise: noise sigma must be a non-negative number");
  cv::Mat value;
  image.convertTo(value, CV_32FC3);
  if (sigma > 0.0) {
    cv::Mat noise(value.size(), CV_32FC3);
    cv::RNG rng(seed);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
    value += noise;
  }
  cv::Mat out;
  value.convertTo(out, CV_8UC3);  // rounds to nearest and saturates to [0, 255]
  return out;
}

}  // namespace reftrack::app
