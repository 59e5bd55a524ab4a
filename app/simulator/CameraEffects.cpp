#include "app/simulator/CameraEffects.hpp"

#include <algorithm>
#include <sstream>

#include "engine/config/ParamFields.hpp"
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

template <class Self, class Field>
void CameraEffects::fields(Self& p, const Field& field) {
  field("photos", p.photos);
  field("photo_file", p.photoFile);
  field("exposure_ms", p.exposureMs, Range{0.0, 1000.0});
  field("readout_ms", p.readoutMs, Range{0.0, 1000.0});
  field("time_samples", p.timeSamples, Range{0, 64});
  field("gain_step", p.gainStep, Range{0.0, 0.9});
  field("gain_step_seconds", p.gainStepSeconds, Range{0.01, 3600.0});
  field("flicker_amplitude", p.flickerAmplitude, Range{0.0, 1.0});
  field("flicker_hz", p.flickerHz, Range{0.1, 10000.0});
  field("vignetting", p.vignetting, Range{0.0, 1.0});
  field("poisson_noise", p.poissonNoise);
  field("conversion_gain", p.conversionGain, Range{0.0, 100.0});
  field("read_noise", p.readNoise, Range{0.0, 100.0});
  field("defocus_radius_px", p.defocusRadiusPx, Range{0.0, 50.0});
  field("codec", p.codec, OneOf{kCodecs});
  field("jpeg_quality", p.jpegQuality, Range{1, 100});
  field("group_frames", p.groupFrames, Range{1, 10000});
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

template struct reftrack::ParamSection<reftrack::app::CameraEffects>;
