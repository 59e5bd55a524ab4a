#pragma once
// SimulationOptions: what `reftrack simulate` renders — camera path preset, frame count, image
// size, seed (sensor noise and hand shake; the scene itself never changes), noise level, motion
// blur, field of view, frame rate, the number of reference views and the lens distortion. check()
// throws reftrack::Error naming the bad field.
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/simulator/CameraEffects.hpp"

namespace reftrack::app {

struct SimulationOptions {
  std::string preset = "handheld";  // handheld | orbit | rotate | static | forward | walkaround
  int frames = 300;
  cv::Size size{640, 480};
  std::uint64_t seed = 1;
  double noiseSigma = 2.0;  // sensor noise SD in grey levels
  bool blur = false;        // motion blur (average of sub-frame renders)
  double fovDeg = 60.0;     // horizontal field of view
  double fps = 30.0;
  int references = 0;  // reference views; 0: the preset's default (walkaround 6, others 2)
  // Distance from reference A to B (metres, sideways); 0: the scene's default (0.25 m).
  double referenceBaseline = 0.0;
  CameraEffects effects;  // webcam effects (CameraEffects; all off by default)
  // Lens distortion, OpenCV order k1,k2,p1,p2[,k3]; empty (or all zero): an ideal pinhole.
  std::vector<double> distortion;
  int referenceCount() const;  // `references`, or the preset's default when it is 0
  void check() const;          // throws reftrack::Error naming the bad field
};

// Reference views a simulation may place (2 .. kMaxReferences).
inline constexpr int kMaxReferences = 16;

// The camera path presets, in the order `reftrack simulate --help` lists them.
const std::vector<std::string>& simulationPresets();

// "640x480" -> 640x480; nullopt unless it is two positive integers joined by 'x'.
std::optional<cv::Size> parseImageSize(const std::string& text);

}  // namespace reftrack::app
