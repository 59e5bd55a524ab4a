#pragma once
// CameraEffectsPipeline: the frames a webcam with CameraEffects records of a scene given by
// renderAt(frame time) (the clean render of the exact pose at that time). Per frame: exposure
// integration (motion blur, rolling shutter), defocus, vignetting x mains flicker x auto-exposure
// gain, sensor noise (Poisson-Gaussian, or the Gaussian `noiseSigma`), 8 bits; then, with a
// codec, groups of frames through the codec and back. Frames are deterministic in (seed, k);
// frames of one codec group are rendered together and kept until another group is asked for.
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "app/simulator/CameraEffects.hpp"
#include "app/simulator/ExposureIntegration.hpp"

namespace reftrack::app {

struct CameraSetup {
  cv::Size size{640, 480};
  double fps = 30.0;
  int frames = 1;  // the sequence length (codec groups end there)
  std::uint64_t seed = 1;
  double noiseSigma = 2.0;  // Gaussian sensor noise when effects.poissonNoise is off
};

class CameraEffectsPipeline {
 public:
  // Throws reftrack::Error for bad effects or setup.
  CameraEffectsPipeline(CameraEffects effects, CameraSetup setup,
                        std::function<cv::Mat(double frameTime)> renderAt);

  cv::Mat frame(int k);  // CV_8UC3; throws outside 0..frames-1
  // A still taken with care (a reference image): defocus, vignetting and sensor noise only.
  cv::Mat still(const cv::Mat& clean, std::uint64_t noiseSeed) const;

  const RowExposureTiming& timing() const { return timing_; }
  int timeSamples() const { return samples_; }
  std::size_t encodedBytes() const { return encodedBytes_; }  // codec groups encoded so far
  int encodedFrames() const { return encodedFrames_; }

 private:
  cv::Mat uncompressed(int k);
  cv::Mat sensor(cv::Mat light, std::uint64_t noiseSeed) const;  // noise + 8 bits

  CameraEffects effects_;
  CameraSetup setup_;
  std::function<cv::Mat(double)> renderAt_;
  RowExposureTiming timing_;
  int samples_ = 1;
  cv::Mat vignetting_;  // CV_32F, empty when off
  int groupStart_ = -1;
  std::vector<cv::Mat> group_;  // decoded frames groupStart_ ...
  std::size_t encodedBytes_ = 0;
  int encodedFrames_ = 0;
};

}  // namespace reftrack::app
