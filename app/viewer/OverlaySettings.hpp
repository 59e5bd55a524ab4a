#pragma once
// OverlaySettings: what the viewer draws over the video — the wireframe cube (default) or an OBJ
// model, its size and placement (by default standing on the scene's dominant plane, scaled to the
// scene: applyScene), and the debug layers (off by default: a clean picture). Saved in the
// `overlay` section of the viewer's parameter file (ViewerSettingsFile.hpp).
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/config/ParamSection.hpp"
#include "engine/mapping/ScenePlacement.hpp"

namespace reftrack::app {

struct OverlaySettings : ParamSection<OverlaySettings> {
  static constexpr const char* kSection = "overlay";

  double size = 0.1;  // metres: cube edge, or the scale of one model unit
  // The object's base centre in the world frame (the cube stands on it: its centre is size/2
  // above, along the object's up axis: world +z, out of the desk, unless placed on the scene).
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  // Placement from the scene (a 6-DOF map's ScenePlacement, applyScene): offset and orientation
  // from its dominant plane, and/or size from its extent. Without a scene they change nothing.
  bool onScene = true;
  bool sizeFromScene = true;
  // Object -> world rotation: the scene plane's axes when placed on it, else identity (upright
  // in the world frame). Not saved: applyScene sets it.
  Eigen::Matrix3d orientation = Eigen::Matrix3d::Identity();
  std::string modelPath;  // OBJ file drawn instead of the cube; "" = wireframe cube
  float lineWidthPx = 3.0f;
  bool vertexDots = true;  // the cube's 8 vertices as dots of distinct colours
  // Debug layers of the tracker (`--debug-overlay` turns on corners, matches and labels).
  bool showCorners = false;
  bool showMatches = false;
  bool showEpipolarLines = false;
  bool showLabels = false;  // frame index, status and tracker name

  // Sets offset and orientation from `scene` when onScene (else orientation = identity), and
  // size when sizeFromScene; nullopt (no map, or no plane found): leaves offset and size alone.
  void applyScene(const std::optional<ScenePlacement>& scene);
  // Corners, matches and labels on or off together (`--debug-overlay`).
  void setDebugLayers(bool on);

  // The cube's model->world transform (rotation `orientation`, centre at offset + size/2 along
  // its up axis).
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
