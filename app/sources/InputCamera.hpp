#pragma once
// cameraFromInput: the camera a `--input` brings with it. A EuRoC input (`euroc:DIR`) carries
// its camera in sensor.yaml (intrinsics, radial-tangential distortion, resolution); commands use
// it when `--camera` is not given, and this says so on stdout ("camera: from ...sensor.yaml").
// Other inputs bring none (nullopt). Throws reftrack::Error for a bad EuRoC layout.
#include <optional>
#include <string>

#include "engine/geometry/PinholeCamera.hpp"

namespace reftrack::app {

std::optional<PinholeCamera> cameraFromInput(const std::string& input);

}  // namespace reftrack::app
