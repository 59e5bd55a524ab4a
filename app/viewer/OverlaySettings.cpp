#include "app/viewer/OverlaySettings.hpp"

#include "engine/config/FieldDescriber.hpp"
#include "engine/config/ParamFields.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

Eigen::Matrix4d OverlaySettings::cubeModelToWorld() const {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = orientation;
  T.block<3, 1>(0, 3) = offset + orientation.col(2) * (size / 2);
  return T;
}

void OverlaySettings::applyScene(const std::optional<ScenePlacement>& scene) {
  orientation = Eigen::Matrix3d::Identity();
  if (!scene) return;
  if (onScene) {
    offset = scene->base;
    orientation = scene->rotation;
  }
  if (sizeFromScene) size = scene->edge;
}

void OverlaySettings::setDebugLayers(bool on) { showCorners = showMatches = showLabels = on; }

std::vector<Eigen::Vector3d> OverlaySettings::cubeWorldVertices() const {
  const Eigen::Matrix4d T = cubeModelToWorld();
  std::vector<Eigen::Vector3d> vertices;
  for (int i = 0; i < 8; ++i) {
    // Bit 0/1/2 of i: +x/+y/+z in the model frame (as render::WireframeCube::worldVertices).
    const Eigen::Vector3d model(i & 1 ? size / 2 : -size / 2, i & 2 ? size / 2 : -size / 2,
                                i & 4 ? size / 2 : -size / 2);
    vertices.push_back(T.topLeftCorner<3, 3>() * model + T.topRightCorner<3, 1>());
  }
  return vertices;
}

template <class Self, class Field>
void OverlaySettings::fields(Self& p, const Field& field) {
  field("size", p.size, Range{1e-6, 1e3})
      .help("Overlay size in metres: the cube's edge, or the length of one model unit");
  field("offset_x", p.offset.x(), Range{-1e3, 1e3})
      .help("Overlay base centre in the world (marker) frame: x (metres)");
  field("offset_y", p.offset.y(), Range{-1e3, 1e3})
      .help("Overlay base centre in the world (marker) frame: y (metres)");
  field("offset_z", p.offset.z(), Range{-1e3, 1e3})
      .help("Overlay base centre in the world (marker) frame: z, out of the desk (metres)");
  field("on_scene", p.onScene, WrittenAsNumber{})
      .help(
          "6-DOF with a map: stand the object on the dominant plane of the map points near "
          "their middle, upright on it (offset_x/y/z are then ignored); 0: at offset_x/y/z, "
          "upright in the world frame");
  field("size_from_scene", p.sizeFromScene, WrittenAsNumber{})
      .help(
          "6-DOF with a map: scale the object to the scene (the plane's map points' median "
          "distance from the base, rounded to 1, 2 or 5 cm, dm, ...; `size` is then ignored); 0: "
          "`size`");
  field("model", p.modelPath).help("OBJ model drawn instead of the wireframe cube; \"\": the cube");
  field("line_width_px", p.lineWidthPx, Range{0.1, 100.0}).help("Overlay line width (pixels)");
  field("vertex_dots", p.vertexDots, WrittenAsNumber{})
      .help("Draw the cube's 8 vertices as dots of distinct colours");
  field("show_corners", p.showCorners, WrittenAsNumber{})
      .help("Draw the frame's corners (debug layer)");
  field("show_matches", p.showMatches, WrittenAsNumber{})
      .help("Draw the matches to the references (debug layer)");
  field("show_epipolar_lines", p.showEpipolarLines, WrittenAsNumber{})
      .help("Draw the epipolar lines (debug layer)");
  field("show_labels", p.showLabels, WrittenAsNumber{})
      .help("Draw the frame index, the tracking status and the tracker's name");
}

void OverlaySettings::read(const YamlNode& node) {
  if (!node.present() || node.isNull()) return;
  if (!node.isMap()) node.fail("section 'overlay' must be a map");
  readFields(*this, node);
  check();
}

}  // namespace reftrack::app

template struct reftrack::ParamSection<reftrack::app::OverlaySettings>;
template void reftrack::app::OverlaySettings::fields(const reftrack::app::OverlaySettings&,
                                                     const reftrack::FieldDescriber&);
