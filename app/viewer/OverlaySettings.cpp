#include "app/viewer/OverlaySettings.hpp"

#include "engine/config/ConfigValue.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

Eigen::Matrix4d OverlaySettings::cubeModelToWorld() const {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.block<3, 1>(0, 3) = offset + Eigen::Vector3d(0, 0, size / 2);
  return T;
}

void OverlaySettings::check() const {
  requireFiniteInRange("overlay.size", size, 1e-6, 1e3);
  for (int i = 0; i < 3; ++i)
    requireFiniteInRange("overlay.offset_" + std::string(1, "xyz"[i]), offset[i], -1e3, 1e3);
  requireFiniteInRange("overlay.line_width_px", lineWidthPx, 0.1, 100.0);
}

void OverlaySettings::write(cv::FileStorage& fs) const {
  fs << "size" << size << "offset_x" << offset.x() << "offset_y" << offset.y() << "offset_z"
     << offset.z() << "model" << modelPath << "line_width_px" << lineWidthPx << "vertex_dots"
     << static_cast<int>(vertexDots) << "show_corners" << static_cast<int>(showCorners)
     << "show_matches" << static_cast<int>(showMatches) << "show_epipolar_lines"
     << static_cast<int>(showEpipolarLines) << "show_labels" << static_cast<int>(showLabels);
}

void OverlaySettings::read(const cv::FileNode& node) {
  if (node.empty() || node.isNone()) return;
  if (!node.isMap()) throw Error("section 'overlay' must be a map");
  const std::string s = "overlay";
  requireKeysWrittenBy(node, s, [](cv::FileStorage& fs) { OverlaySettings{}.write(fs); });
  readConfigValue(node, s, "size", size);
  readConfigValue(node, s, "offset_x", offset.x());
  readConfigValue(node, s, "offset_y", offset.y());
  readConfigValue(node, s, "offset_z", offset.z());
  readConfigValue(node, s, "model", modelPath);
  double width = lineWidthPx;
  readConfigValue(node, s, "line_width_px", width);
  lineWidthPx = static_cast<float>(width);
  readConfigValue(node, s, "vertex_dots", vertexDots);
  readConfigValue(node, s, "show_corners", showCorners);
  readConfigValue(node, s, "show_matches", showMatches);
  readConfigValue(node, s, "show_epipolar_lines", showEpipolarLines);
  readConfigValue(node, s, "show_labels", showLabels);
  check();
}

}  // namespace reftrack::app
