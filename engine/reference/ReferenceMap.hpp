#pragma once
// ReferenceMap: what the 6-DOF tracker knows before it starts (paper Sec. 2, 3.3) — the two
// reference images V_A, V_B, the camera, their world->camera poses T_A, T_B, the corners of both,
// the A<->B matches and one 3D point per match (in camera A's frame). On disk: a folder with
// map.yml (OpenCV FileStorage, versioned) and the two images beside it. Saving writes the images
// first and map.yml last, each atomically, so an interrupted save never leaves a loadable half map.
#include <Eigen/Core>
#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/config/CornerParams.hpp"
#include "engine/config/YamlNode.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

struct ReferenceCorner {
  cv::Point2f pixel;         // as detected (with lens distortion)
  float rmsContrast = 0.0f;  // of the 15x15 window around it (grey levels)
};

struct ReferenceMatch {
  int cornerA = -1, cornerB = -1;  // indices into cornersA / cornersB
  Eigen::Vector3d pointA;          // triangulated 3D point in camera A's frame (metres)
  // Where the point was measured in A and B (pixels, with lens distortion): the correlation peaks
  // it was triangulated from (MultiReferenceMap's PointObservation::peak). None: the corner. Not
  // written by save() (format 1); the tracker's epipolar terms measure the reference at them.
  std::optional<cv::Point2f> peakA{}, peakB{};
};

class ReferenceMap {
 public:
  static constexpr int kFormatVersion = 1;
  static constexpr const char* kFileName = "map.yml";

  PinholeCamera camera;
  RigidPose T_A, T_B;  // world -> camera of V_A, V_B
  cv::Mat imageA, imageB;
  std::vector<ReferenceCorner> cornersA, cornersB;
  std::vector<ReferenceMatch> matches;
  std::string poseSource;         // e.g. "marker DICT_6X6_250:23:0.12" or "poses references.txt"
  std::string preparationParams;  // the parameters used, as YAML text (for the record)
  // Set when the references' corners were detected denser than the preparation's corners (soft
  // images: MultiReferencePreparer): the tracker detects the frames' corners at least as densely,
  // or few of its corners are those the map's points lie on. Kept by MultiReferenceMap's file,
  // not by this class's own (version 1).
  std::optional<CornerParams> denserCorners{};

  RigidPose T_AB() const { return T_B * T_A.inverse(); }

  // Throws reftrack::Error naming what is inconsistent (sizes, indices, NaNs, ...).
  void check() const;
  void save(const std::filesystem::path& folder) const;
  // Checks the version and every field; refuses missing images and size mismatches.
  static ReferenceMap load(const std::filesystem::path& folder);
};

// Opens a map.yml (either format version) for reading; throws reftrack::Error naming the file
// when it is missing, cannot be opened or is corrupt.
YamlNode openReferenceMapFile(const std::filesystem::path& file);

}  // namespace reftrack
