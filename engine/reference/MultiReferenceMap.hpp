#pragma once
// MultiReferenceMap (issue 13): N >= 2 calibrated reference images with their world->camera
// poses and corners, the 3D points triangulated from every pair of references with overlap and
// parallax (each point keeps its corner in every reference that sees it), and the keypoint layer
// used for relocalisation. The 6-DOF tracker runs the paper's two-reference costs on one pair at a
// time: pair(a, b) is that pair as a two-view ReferenceMap. On disk (format version 3): a folder
// with map.yml and one image per reference; load() also reads version-2 maps (no peaks) and
// version-1 (two-reference) maps.
#include <Eigen/Core>
#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/config/CornerParams.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/ReferenceMap.hpp"
#include "engine/relocalisation/ReferenceKeypoints.hpp"

namespace reftrack {

struct PointObservation {
  int view = -1;    // index into MultiReferenceMap::views
  int corner = -1;  // index into that view's corners
  // Where the point was measured in this view (pixels, with lens distortion): the sub-pixel
  // correlation peak its triangulation used, up to matching.max_peak_offset_px from the corner
  // (the corner itself in the view that anchored the match). None: the corner (format 1/2 maps).
  std::optional<cv::Point2f> peak{};
};

struct MapPoint {
  Eigen::Vector3d world = Eigen::Vector3d::Zero();  // metres, world frame
  std::vector<PointObservation> observations;       // at least two views, each at most once
};

struct ReferenceView {
  std::string name;      // the image's file name inside the map folder, e.g. "reference_03.png"
  RigidPose T;           // world -> camera
  bool anchored = true;  // pose given (marker / --poses); false: added by `extend` and refined
  cv::Mat image;         // as captured (BGR or grey), the camera's image size
  std::vector<ReferenceCorner> corners;
  ReferenceKeypoints keypoints;  // may be empty (then the view cannot relocalise)
};

class MultiReferenceMap {
 public:
  static constexpr int kFormatVersion = 3;
  static constexpr const char* kFileName = "map.yml";

  PinholeCamera camera;
  std::vector<ReferenceView> views;
  std::vector<MapPoint> points;
  std::string keypointKind;       // detector/descriptor of every view's keypoints, e.g. "orb"
  std::string poseSource;         // e.g. "marker DICT_6X6_250:23:0.2" or "poses references.txt"
  std::string preparationParams;  // the parameters used, as YAML text (for the record)
  // The corners the references were detected with when denser than the preparation's own
  // (ReferenceMap::denserCorners); map.yml's optional `denser_corners` section.
  std::optional<CornerParams> denserCorners{};

  int size() const { return static_cast<int>(views.size()); }
  // The two-view map the paper's costs run on: views a (as V_A) and b (as V_B), their corners,
  // and one match per map point that both see (its 3D point in camera a's frame). Throws
  // reftrack::Error when a == b or either is out of range.
  ReferenceMap pair(int a, int b) const;
  // The pixel (with lens distortion) observation `o` measured: its peak, or else its corner.
  // `o` must name an existing view and corner (check()).
  cv::Point2f measuredPixel(const PointObservation& o) const;
  // Number of map points seen by both a and b.
  int sharedPoints(int a, int b) const;
  // A two-reference map (version 1) as an N = 2 map: points from its matches, no keypoints.
  static MultiReferenceMap fromPair(const ReferenceMap& map);

  // Throws reftrack::Error naming what is inconsistent (sizes, indices, NaNs, duplicates, ...).
  void check() const;
  // Writes the images first and map.yml last, each atomically: an interrupted save never leaves
  // a loadable half map.
  void save(const std::filesystem::path& folder) const;
  // Version 3; version 2 (observations without peaks); version 1 through fromPair(). Checks the
  // version and every field.
  static MultiReferenceMap load(const std::filesystem::path& folder);
};

}  // namespace reftrack
