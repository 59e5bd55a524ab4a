#pragma once
// CameraEffects: what a real webcam does to the simulator's ideal image, each effect switchable
// (zero / false / "none" = off) and none of them moving the ground truth: real photographs as
// scene textures, motion blur over the exposure, rolling shutter, auto-exposure gain steps, mains
// flicker, vignetting, Poisson-Gaussian sensor noise, defocus and video compression. Times are
// seconds-based so the levels do not depend on the frame rate; pixel sizes are at the image size
// they were made for (cameraEffectsFor scales them). check() throws reftrack::Error naming the bad
// field (effects.key); read() / write() use the same keys in a FileStorage map.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "engine/config/ParamSection.hpp"

namespace reftrack::app {

struct CameraEffects : ParamSection<CameraEffects> {
  static constexpr const char* kSection = "effects";

  bool photos = false;            // photo prints on the desk (assets/textures/, see their README)
  std::string photoFile;          // "" = the bundled photograph
  double exposureMs = 0.0;        // motion blur: each row integrates the path over this exposure
  double readoutMs = 0.0;         // rolling shutter: row r starts r * readout / (rows - 1) later
  int timeSamples = 0;            // renders per frame for blur / rolling shutter; 0 = automatic
  double gainStep = 0.0;          // auto-exposure: gain level in [1 - a, 1 + a], piecewise constant
  double gainStepSeconds = 1.5;   // ... changing every this many seconds (level 1 in the first)
  double flickerAmplitude = 0.0;  // mains flicker: light = 1 + a cos(2 pi f t)
  double flickerHz = 100.0;       // twice the mains frequency (50 Hz mains)
  double vignetting = 0.0;        // relative light loss at the image corners (quadratic in r)
  bool poissonNoise = false;      // signal-dependent noise replacing the Gaussian noiseSigma:
  double conversionGain = 0.05;   // grey levels per electron (shot-noise variance = gain * I)
  double readNoise = 1.5;         // read noise SD, grey levels
  double defocusRadiusPx = 0.0;   // disc (circle of confusion) radius, pixels
  std::string codec = "none";     // none | h264 | mp4v (OpenCV FFmpeg writer) | mjpeg (JPEG)
  int jpegQuality = 75;           // mjpeg
  int groupFrames = 30;           // h264 / mp4v: frames encoded together (one key frame each)

  bool motionDependent() const { return exposureMs > 0.0 || readoutMs > 0.0; }
  bool any() const;                   // true when at least one effect is on
  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
  std::string key() const;  // a short text naming every non-default value (cache key)
};

// The effect names `--effects` accepts, each switching on one effect at its webcam level:
// photos, blur, rolling-shutter, exposure, flicker, vignetting, noise, defocus, compression.
const std::vector<std::string>& cameraEffectNames();

// "none", "webcam" (every effect at typical webcam levels) or a comma-separated list of effect
// names, at the levels for `size` (defocus scales with the width; 640x480 levels otherwise).
// Throws reftrack::Error naming an unknown effect.
CameraEffects cameraEffectsFor(const std::string& list, cv::Size size);

}  // namespace reftrack::app

// Defined in CameraEffects.cpp.
extern template struct reftrack::ParamSection<reftrack::app::CameraEffects>;
