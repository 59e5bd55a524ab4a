#include "app/simulator/CameraEffectsPipeline.hpp"

#include "app/simulator/PhotometricEffects.hpp"
#include "app/simulator/SensorNoise.hpp"
#include "app/simulator/VideoCodecRoundTrip.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

CameraEffectsPipeline::CameraEffectsPipeline(CameraEffects effects, CameraSetup setup,
                                             std::function<cv::Mat(double)> renderAt)
    : effects_(std::move(effects)), setup_(setup), renderAt_(std::move(renderAt)) {
  effects_.check();
  if (setup_.size.width < 1 || setup_.size.height < 1 || !(setup_.fps > 0.0) || setup_.frames < 1)
    throw Error("camera effects: bad image size, frame rate or frame count");
  timing_.rows = setup_.size.height;
  timing_.exposureFrames = effects_.exposureMs * 1e-3 * setup_.fps;
  timing_.lineDelayFrames =
      timing_.rows > 1 ? effects_.readoutMs * 1e-3 * setup_.fps / (timing_.rows - 1) : 0.0;
  timing_.check();
  samples_ = effects_.timeSamples > 0 && effects_.motionDependent() ? effects_.timeSamples
                                                                    : timing_.automaticSamples();
  if (effects_.vignetting > 0.0) vignetting_ = vignettingGain(setup_.size, effects_.vignetting);
}

cv::Mat CameraEffectsPipeline::sensor(cv::Mat light, std::uint64_t noiseSeed) const {
  if (effects_.poissonNoise)
    return addPoissonGaussianNoise(light, noiseSeed, effects_.conversionGain, effects_.readNoise);
  return addSensorNoise(light, noiseSeed, setup_.noiseSigma);
}

cv::Mat CameraEffectsPipeline::still(const cv::Mat& clean, std::uint64_t noiseSeed) const {
  cv::Mat light;
  clean.convertTo(light, CV_32FC3);
  light = defocus(light, effects_.defocusRadiusPx);
  if (!vignetting_.empty()) {
    cv::Mat gain3;
    cv::merge(std::vector<cv::Mat>(3, vignetting_), gain3);
    light = light.mul(gain3);
  }
  return sensor(light, noiseSeed);
}

cv::Mat CameraEffectsPipeline::uncompressed(int k) {
  cv::Mat light = integrateExposure(renderAt_, k, timing_, samples_);
  light = defocus(light, effects_.defocusRadiusPx);
  // Vignetting x flicker (per row) x auto-exposure gain, one CV_32F gain image.
  cv::Mat gain =
      vignetting_.empty() ? cv::Mat(setup_.size, CV_32F, cv::Scalar(1.0)) : vignetting_.clone();
  if (effects_.flickerAmplitude > 0.0) {
    const cv::Mat rows =
        flickerRowGain(timing_, k, setup_.fps, effects_.flickerAmplitude, effects_.flickerHz);
    for (int r = 0; r < gain.rows; ++r) gain.row(r) *= rows.at<float>(r);
  }
  gain *=
      autoExposureGain(setup_.seed, k / setup_.fps, effects_.gainStep, effects_.gainStepSeconds);
  cv::Mat gain3;
  cv::merge(std::vector<cv::Mat>(3, gain), gain3);
  return sensor(light.mul(gain3), mixSeed(setup_.seed, static_cast<std::uint64_t>(k)));
}

cv::Mat CameraEffectsPipeline::frame(int k) {
  if (k < 0 || k >= setup_.frames)
    throw Error("camera effects: frame " + std::to_string(k) + " is outside 0.." +
                std::to_string(setup_.frames - 1));
  if (effects_.codec == "none") return uncompressed(k);
  const int group = effects_.codec == "mjpeg" ? 1 : effects_.groupFrames;
  const int start = k / group * group;
  if (start != groupStart_) {
    std::vector<cv::Mat> raw;
    for (int i = start; i < std::min(start + group, setup_.frames); ++i)
      raw.push_back(uncompressed(i));
    EncodedVideo encoded = roundTripVideo(raw, effects_.codec, setup_.fps, effects_.jpegQuality);
    encodedBytes_ += encoded.bytes;
    encodedFrames_ += static_cast<int>(raw.size());
    group_ = std::move(encoded.frames);
    groupStart_ = start;
  }
  return group_[static_cast<std::size_t>(k - start)].clone();
}

}  // namespace reftrack::app
