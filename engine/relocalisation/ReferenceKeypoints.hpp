#pragma once
// ReferenceKeypoints: the viewpoint-invariant keypoint layer of one reference image (issue 13):
// keypoints, their descriptors and, where preparation could triangulate one, the keypoint's 3D
// point in the world frame (NaN otherwise). Stored in the map at prepare time so relocalisation
// never re-detects the references. write() writes an OpenCV FileStorage node, read() reads it
// back from the map file (YamlNode).
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "engine/config/YamlNode.hpp"

namespace reftrack {

struct ReferenceKeypoints {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;                  // one row per keypoint (CV_8U binary or CV_32F)
  std::vector<Eigen::Vector3d> points;  // world frame, one per keypoint; NaN where none

  bool empty() const { return keypoints.empty(); }
  int pointCount() const;  // keypoints with a finite 3D point
  // Throws reftrack::Error naming `name` when sizes disagree or a keypoint is not finite.
  void check(const std::string& name) const;
  // Writes a map node named `name` holding the whole layer (compact: rows of numbers).
  void write(cv::FileStorage& fs, const std::string& name) const;
  // Reads what write() wrote; throws reftrack::Error naming the field at fault (by node.name()).
  static ReferenceKeypoints read(const YamlNode& node);
};

}  // namespace reftrack
