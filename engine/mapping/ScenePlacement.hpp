#pragma once
// ScenePlacement: where a virtual object stands by default in a map's scene — on the dominant
// plane (RANSAC, then least squares) of the map points nearest their median, its base centre the
// plane inliers' mean (on the least-squares plane), its up axis the plane normal on the side of
// the reference cameras, its x axis the world x laid onto the plane, and its edge the inliers'
// median distance from the base on the plane, rounded to 1, 2 or 5 x 10^k metres.
#include <Eigen/Core>
#include <vector>

namespace reftrack {

class MultiReferenceMap;

struct ScenePlacement {
  Eigen::Vector3d base = Eigen::Vector3d::Zero();          // on the plane (world, metres)
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // object -> world; column 2: up
  double edge = 0.1;                                       // metres
  int consideredPoints = 0;  // the points nearest the median that the plane was fitted to
  int planePoints = 0;       // of those, within planeThresholdMetres of the plane
  double planeThresholdMetres = 0.0;
  double planeRmsMetres = 0.0;  // the inliers' RMS distance to the fitted plane
};

// `cameraCentres` (world) choose the plane's up side (their mean; none: world +z's side). Throws
// reftrack::Error when fewer than 12 finite points are given or no plane holds a quarter of the
// points considered.
ScenePlacement placeOnDominantPlane(const std::vector<Eigen::Vector3d>& points,
                                    const std::vector<Eigen::Vector3d>& cameraCentres);

// The map's points, with its references' centres as the cameras.
ScenePlacement placeOnDominantPlane(const MultiReferenceMap& map);

}  // namespace reftrack
