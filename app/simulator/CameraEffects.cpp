#include "app/simulator/CameraEffects.hpp"

#include <algorithm>
#include <sstream>

#include "engine/config/ConfigValue.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

// Typical levels of a USB webcam indoors at 640x480 / 30 fps (the `webcam` preset):
constexpr double kWebcamExposureMs = 16.0;  // 1/60 s, room light
constexpr double kWebcamReadoutMs = 20.0;   // rolling-shutter frame readout of a CMOS webcam
constexpr double kWebcamGainStep = 0.08;    // auto-exposure adjusts by ~1/8 stop
constexpr double kWebcamFlicker = 0.10;     // LED / fluorescent light modulation at 100 Hz
constexpr double kWebcamVignetting = 0.30;  // corners get 70% of the centre's light
constexpr double kWebcamDefocusPx = 0.8;    // fixed-focus lens, circle of confusion at 640 px

const std::vector<std::string> kCodecs = {"none", "h264", "mp4v", "mjpeg"};

}  // namespace

bool CameraEffects::any() const {
  return photos || motionDependent() || gainStep > 0.0 || flickerAmplitude > 0.0 ||
         vignetting > 0.0 || poissonNoise || defocusRadiusPx > 0.0 || codec != "none";
}

void CameraEffects::check() const {
  requireFiniteInRange("effects.exposure_ms", exposureMs, 0.0, 1000.0);
  requireFiniteInRange("effects.readout_ms", readoutMs, 0.0, 1000.0);
  requireIntInRange("effects.time_samples", timeSamples, 0, 64);
  requireFiniteInRange("effects.gain_step", gainStep, 0.0, 0.9);
  requireFiniteInRange("effects.gain_step_seconds", gainStepSeconds, 0.01, 3600.0);
  requireFiniteInRange("effects.flicker_amplitude", flickerAmplitude, 0.0, 1.0);
  requireFiniteInRange("effects.flicker_hz", flickerHz, 0.1, 10000.0);
  requireFiniteInRange("effects.vignetting", vignetting, 0.0, 1.0);
  requireFiniteInRange("effects.conversion_gain", conversionGain, 0.0, 100.0);
  requireFiniteInRange("effects.read_noise", readNoise, 0.0, 100.0);
  requireFiniteInRange("effects.defocus_radius_px", defocusRadiusPx, 0.0, 50.0);
  if (std::find(kCodecs.begin(), kCodecs.end(), codec) == kCodecs.end())
    throw Error("effects.codec must be none, h264, mp4v or mjpeg, got '" + codec + "'");
  requireIntInRange("effects.jpeg_quality", jpegQuality, 1, 100);
  requireIntInRange("effects.group_frames", groupFrames, 1, 10000);
}

void CameraEffects::write(cv::FileStorage& fs) const {
  fs << "photos" << (photos ? "true" : "false") << "photo_file" << photoFile << "exposure_ms"
     << exposureMs << "readout_ms" << readoutMs << "time_samples" << timeSamples << "gain_step"
     << gainStep << "gain_step_seconds" << gainStepSeconds << "flicker_amplitude"
     << flickerAmplitude << "flicker_hz" << flickerHz << "vignetting" << vignetting
     << "poisson_noise" << (poissonNoise ? "true" : "false") << "conversion_gain" << conversionGain
     << "read_noise" << readNoise << "defocus_radius_px" << defocusRadiusPx << "codec" << codec
     << "jpeg_quality" << jpegQuality << "group_frames" << groupFrames;
}

void CameraEffects::read(const cv::FileNode& node) {
  const std::string s = "effects";
  readConfigValue(node, s, "photos", photos);
  readConfigValue(node, s, "photo_file", photoFile);
  readConfigValue(node, s, "exposure_ms", exposureMs);
  readConfigValue(node, s, "readout_ms", readoutMs);
  readConfigValue(node, s, "time_samples", timeSamples);
  readConfigValue(node, s, "gain_step", gainStep);
  readConfigValue(node, s, "gain_step_seconds", gainStepSeconds);
  readConfigValue(node, s, "flicker_amplitude", flickerAmplitude);
  readConfigValue(node, s, "flicker_hz", flickerHz);
  readConfigValue(node, s, "vignetting", vignetting);
  readConfigValue(node, s, "poisson_noise", poissonNoise);
  readConfigValue(node, s, "conversion_gain", conversionGain);
  readConfigValue(node, s, "read_noise", readNoise);
  readConfigValue(node, s, "defocus_radius_px", defocusRadiusPx);
  readConfigValue(node, s, "codec", codec);
  readConfigValue(node, s, "jpeg_quality", jpegQuality);
  readConfigValue(node, s, "group_frames", groupFrames);
  check();
}

std::string CameraEffects::key() const {
  if (!any()) return "";
  std::ostringstream k;
  if (photos) k << "_photos" << photoFile;
  if (exposureMs > 0) k << "_exp" << exposureMs;
  if (readoutMs > 0) k << "_rs" << readoutMs;
  if (motionDependent() && timeSamples > 0) k << "_ts" << timeSamples;
  if (gainStep > 0) k << "_gain" << gainStep << "x" << gainStepSeconds;
  if (flickerAmplitude > 0) k << "_flicker" << flickerAmplitude << "x" << flickerHz;
  if (vignetting > 0) k << "_vig" << vignetting;
  if (poissonNoise) k << "_pg" << conversionGain << "x" << readNoise;
  if (defocusRadiusPx > 0) k << "_defocus" << defocusRadiusPx;
  if (codec != "none") k << "_" << codec << (codec == "mjpeg" ? jpegQuality : groupFrames);
  return k.str();
}

const std::vector<std::string>& cameraEffectNames() {
  static const std::vector<std::string> names = {"photos",   "blur",    "rolling-shutter",
                                                 "exposure", "flicker", "vignetting",
                                                 "noise",    "defocus", "compression"};
  return names;
}

CameraEffects cameraEffectsFor(const std::string& list, cv::Size size) {
  CameraEffects e;
  if (list.empty() || list == "none") return e;
  std::vector<std::string> names;
  if (list == "webcam") {
    names = cameraEffectNames();
  } else {
    std::stringstream in(list);
    for (std::string name; std::getline(in, name, ',');) names.push_back(name);
  }
  for (const std::string& name : names) {
    if (name == "photos") {
      e.photos = true;
    } else if (name == "blur") {
      e.exposureMs = kWebcamExposureMs;
    } else if (name == "rolling-shutter") {
      e.readoutMs = kWebcamReadoutMs;
    } else if (name == "exposure") {
      e.gainStep = kWebcamGainStep;
    } else if (name == "flicker") {
      e.flickerAmplitude = kWebcamFlicker;
    } else if (name == "vignetting") {
      e.vignetting = kWebcamVignetting;
    } else if (name == "noise") {
      e.poissonNoise = true;
    } else if (name == "defocus") {
      e.defocusRadiusPx = kWebcamDefocusPx * size.width / 640.0;
    } else if (name == "compression") {
      e.codec = "h264";
    } else {
      std::string known = "none, webcam";
      for (const std::string& n : cameraEffectNames()) known += ", " + n;
      throw Error("camera effect '" + name + "' is unknown (known: " + known + ")");
    }
  }
  e.check();
  return e;
}

}  // namespace reftrack::app
