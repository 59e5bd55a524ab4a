#pragma once
// OverlaySettings: what the viewer draws over the video — the wireframe cube (default) or an OBJ
// model, its size and placement in the world (marker) frame, and the debug layers. Saved in the
// `overlay` section of the viewer's parameter file (ViewerSettingsFile.hpp).
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "engine/config/ParamSection.hpp"

namespace reftrack::app {

struct OverlaySettings : ParamSection<OverlaySettings> {
  static constexpr const char* kSection = "overlay";

  double size = 0.1;  // metres: cube edge, or the scale of one model unit
  // The object's base centre in the world frame (the cube stands on it: its centre is size/2
  // above, along world +z, out of the desk).
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  std::string modelPath;  // OBJ file drawn instead of the cube; "" = wireframe cube
  float lineWidthPx = 3.0f;
  bool vertexDots = true;  // the cube's 8 vertices as dots of distinct colours
  bool showCorners = true;
  bool showMatches = true;
  bool showEpipolarLines = false;
  bool showLabels = true;  // frame index, status and tracker name

  // The cube's model->world transform (centre at offset + size/2 along +z).
  Eigen::Matrix4d cubeModelToWorld() const;
  // The points the predicted overlay error is computed for: the cube's 8 vertices in the world
  // (for an OBJ model, the cube of the same size and place stands in for its extent).
  std::vector<Eigen::Vector3d> cubeWorldVertices() const;
  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
  // As ParamSection's, but an absent section is left alone and one that is not a map refused.
  void read(const YamlNode& node);
};

}  // namespace reftrack::app

// Defined in OverlaySettings.cpp.
extern template struct reftrack::ParamSection<reftrack::app::OverlaySettings>;
