#pragma once
// PhotometricEffects: the optics and sensor of a webcam applied to a rendered CV_32FC3 image
// (grey levels 0..255): defocus (a disc, the circle of confusion), vignetting, the auto-exposure
// gain, mains flicker integrated over each row's exposure, and Poisson-Gaussian sensor noise.
// None of them moves the image geometrically, so the ground truth is untouched.
#include <cstdint>
#include <opencv2/core.hpp>

#include "app/simulator/ExposureIntegration.hpp"

namespace reftrack::app {

// CV_32F disc of radius `radiusPx` (> 0) summing to 1, its edge pixels weighted by the covered
// area (8 x 8 sub-pixel samples), size 2 ceil(radius) + 1.
cv::Mat defocusKernel(double radiusPx);
// `image` convolved with defocusKernel (borders reflected); radius 0 returns it unchanged.
cv::Mat defocus(const cv::Mat& image, double radiusPx);

// CV_32F relative illumination 1 - strength (r / r_corner)^2, r from the image centre.
cv::Mat vignettingGain(cv::Size size, double strength);

// Auto-exposure gain at `seconds`: 1 during the first `stepSeconds`, then a level drawn
// uniformly in [1 - step, 1 + step] per interval (seeded, deterministic).
double autoExposureGain(std::uint64_t seed, double seconds, double step, double stepSeconds);

// CV_32F column (timing.rows x 1): each row's mean of the light 1 + a cos(2 pi hz t) over its
// exposure window (t in seconds = frame time / fps; the instantaneous value without exposure).
cv::Mat flickerRowGain(const RowExposureTiming& timing, double frameTime, double fps,
                       double amplitude, double hz);

// CV_8UC3: `image` plus zero-mean noise of variance conversionGain * max(I, 0) + readNoise^2 per
// pixel and channel (shot noise of I / conversionGain electrons in its Gaussian approximation,
// exact in mean and variance, plus read noise), rounded and clamped; drawn from cv::RNG(seed).
cv::Mat addPoissonGaussianNoise(const cv::Mat& image, std::uint64_t seed, double conversionGain,
                                double readNoise);

}  // namespace reftrack::app
