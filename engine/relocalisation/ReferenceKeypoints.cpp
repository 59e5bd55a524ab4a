#include "engine/relocalisation/ReferenceKeypoints.hpp"

#include <cmath>
#include <limits>

#include "engine/config/KnownKeys.hpp"
#include "engine/config/YamlMatrix.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

int ReferenceKeypoints::pointCount() const {
  int n = 0;
  for (const Eigen::Vector3d& p : points) n += p.allFinite() ? 1 : 0;
  return n;
}

void ReferenceKeypoints::check(const std::string& name) const {
  if (points.size() != keypoints.size())
    throw Error(name + ": " + std::to_string(points.size()) + " points for " +
                std::to_string(keypoints.size()) + " keypoints");
  if (descriptors.rows != static_cast<int>(keypoints.size()))
    throw Error(name + ": " + std::to_string(descriptors.rows) + " descriptors for " +
                std::to_string(keypoints.size()) + " keypoints");
  if (!keypoints.empty() && descriptors.type() != CV_8U && descriptors.type() != CV_32F)
    throw Error(name + ": descriptors must be CV_8U or CV_32F");
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    const cv::KeyPoint& k = keypoints[i];
    if (!std::isfinite(k.pt.x) || !std::isfinite(k.pt.y) || !std::isfinite(k.size) ||
        !std::isfinite(k.angle) || !std::isfinite(k.response))
      throw Error(name + ".keypoints[" + std::to_string(i) + "] is not finite");
  }
}

void ReferenceKeypoints::write(cv::FileStorage& fs, const std::string& name) const {
  check(name);
  // keypoints: one row each (x, y, size, angle, response, octave); points: (x, y, z), NaN = none.
  cv::Mat kp(static_cast<int>(keypoints.size()), 6, CV_32F);
  cv::Mat pts(static_cast<int>(points.size()), 3, CV_64F);
  for (int i = 0; i < kp.rows; ++i) {
    const cv::KeyPoint& k = keypoints[static_cast<std::size_t>(i)];
    const float row[6] = {k.pt.x,  k.pt.y,     k.size,
                          k.angle, k.response, static_cast<float>(k.octave)};
    for (int c = 0; c < 6; ++c) kp.at<float>(i, c) = row[c];
    for (int c = 0; c < 3; ++c) pts.at<double>(i, c) = points[static_cast<std::size_t>(i)][c];
  }
  fs << name << "{";
  fs << "count" << static_cast<int>(keypoints.size());
  fs << "keypoints" << kp << "descriptors" << descriptors << "points" << pts;
  fs << "}";
}

ReferenceKeypoints ReferenceKeypoints::read(const YamlNode& node) {
  const std::string& name = node.name();
  if (!node.isMap()) node.fail(name + ": missing or not a map");
  requireKnownKeys(node, {"count", "keypoints", "descriptors", "points"});
  ReferenceKeypoints r;
  const int count = node["count"].integer().value_or(-1);
  if (count < 0) node.fail(name + ".count: missing or negative");
  if (count == 0) return r;
  const cv::Mat kp = readYamlMatrix(node["keypoints"]), pts = readYamlMatrix(node["points"]);
  r.descriptors = readYamlMatrix(node["descriptors"]);
  if (kp.rows != count || kp.cols != 6 || kp.type() != CV_32F)
    node["keypoints"].fail(name + ".keypoints: expected " + std::to_string(count) + "x6 floats");
  if (pts.rows != count || pts.cols != 3 || pts.type() != CV_64F)
    node["points"].fail(name + ".points: expected " + std::to_string(count) + "x3 doubles");
  for (int i = 0; i < count; ++i) {
    cv::KeyPoint k;
    k.pt = {kp.at<float>(i, 0), kp.at<float>(i, 1)};
    k.size = kp.at<float>(i, 2);
    k.angle = kp.at<float>(i, 3);
    k.response = kp.at<float>(i, 4);
    k.octave = static_cast<int>(kp.at<float>(i, 5));
    r.keypoints.push_back(k);
    r.points.emplace_back(pts.at<double>(i, 0), pts.at<double>(i, 1), pts.at<double>(i, 2));
  }
  r.check(name);
  return r;
}

}  // namespace reftrack
