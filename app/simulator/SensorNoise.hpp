#pragma once
// Camera sensor model of the simulator: additive Gaussian noise on every channel, then rounding
// and clamping to 8 bits. Seeds are mixed (SplitMix64) so that nearby (seed, frame) pairs give
// unrelated noise streams.
#include <cstdint>
#include <opencv2/core.hpp>

namespace reftrack::app {

// A well-mixed 64-bit seed from two values; mixSeed(a, b) != mixSeed(b, a) in general.
std::uint64_t mixSeed(std::uint64_t a, std::uint64_t b);

// `image`: CV_8UC3 or CV_32FC3 (grey levels 0..255). Returns CV_8UC3 with N(0, sigma^2) added
// per channel and pixel, drawn from cv::RNG(seed). sigma = 0 only rounds and clamps.
cv::Mat addSensorNoise(const cv::Mat& image, std::uint64_t seed, double sigma);

}  // namespace reftrack::app
