#pragma once
// MapFileFields: the map.yml fields both map formats share (version 1: ReferenceMap, version 2:
// MultiReferenceMap) — the camera, 4x4 poses, corner lists and reference images — written and
// read by one function each, so both loaders refuse bad input with the same messages. Every
// reader error names the file (`where`) and the field ("reference map 'x/map.yml': field 'T_A'
// is not finite").
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "engine/config/YamlNode.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/ReferenceMap.hpp"

namespace reftrack {

// Writes image_width, image_height, camera_matrix and distortion_coefficients.
void writeMapCamera(cv::FileStorage& fs, const PinholeCamera& camera);
// A pose as its 4x4 matrix (CV_64F).
cv::Mat poseToMat(const RigidPose& T);
// Corners as rows (x, y, rmsContrast), CV_32F.
cv::Mat cornersToMat(const std::vector<ReferenceCorner>& corners);
// True when p lies on the image (pixel centres at integers: [-0.5, size - 0.5]).
bool liesInsideImage(cv::Point2f p, cv::Size size);
// Throws reftrack::Error "name[i] is not finite" / "name[i] lies outside the image".
void checkCorners(const std::vector<ReferenceCorner>& corners, const std::string& name,
                  cv::Size imageSize);

// Reads the fields of one map.yml; `name` is a field's dotted name in messages ("views[2].T").
class MapFieldReader {
 public:
  MapFieldReader(std::string where, std::filesystem::path folder)
      : where_(std::move(where)), folder_(std::move(folder)) {}

  const std::string& where() const { return where_; }
  // requireKnownKeys, its message prefixed with where().
  void requireKnown(const YamlNode& node, const std::vector<std::string>& known) const;
  // parent[key]; throws "missing field 'name' (truncated file?)" when absent.
  YamlNode need(const YamlNode& parent, const std::string& key, const std::string& name) const;
  // A matrix (YamlMatrix.hpp) with `rows` x `cols` (-1: any; an empty matrix passes any cols).
  cv::Mat readMat(const YamlNode& parent, const std::string& key, const std::string& name, int rows,
                  int cols) const;
  // parent[key] as an integer or as text; throws naming the field otherwise.
  int readInt(const YamlNode& parent, const std::string& key, const std::string& name) const;
  std::string readText(const YamlNode& parent, const std::string& key,
                       const std::string& name) const;
  // The camera writeMapCamera() wrote at the root (not checked: the map's check() does that).
  PinholeCamera readCamera(const YamlNode& root) const;
  // A finite rigid 4x4 transform.
  RigidPose readPose(const YamlNode& parent, const std::string& key, const std::string& name) const;
  std::vector<ReferenceCorner> readCorners(const YamlNode& parent, const std::string& key,
                                           const std::string& name) const;
  // The image `fileName` beside map.yml; `name` is the field that named it.
  cv::Mat readImage(const std::string& fileName, const std::string& name) const;

 private:
  std::string where_;
  std::filesystem::path folder_;
};

// Runs readFields(map) on a default Map, then map.check(); a failed check becomes a
// reftrack::Error naming `where`.
template <class Map, class ReadFields>
Map readCheckedMap(const std::string& where, ReadFields&& readFields) {
  Map map;
  readFields(map);
  try {
    map.check();
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  return map;
}

}  // namespace reftrack
