#pragma once
// Building the keypoint layer of a MultiReferenceMap at prepare time (issue 13): every view's
// keypoints are detected and described, matched to every other view's (ratio test + mutual),
// the matches consistent with the known poses (epipolar distance) are triangulated, and a
// keypoint keeps the 3D point of its best-conditioned match (largest parallax) that lies in front
// of both cameras and reprojects within tolerance in both; NaN where none.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>

#include "engine/config/RelocalisationParams.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack {

// Builds the keypoint layer of every view of `map` (detect, describe, triangulate each keypoint
// from the views that see it under the known poses); replaces views[i].keypoints and
// map.keypointKind. Throws reftrack::Error for a map with fewer than two views or an image of
// another size than the camera's.
void buildReferenceKeypoints(MultiReferenceMap& map, const RelocalisationParams& params);

// One match of two views with world->camera poses Ti, Tj at ideal (undistorted) pixels xi, xj:
// its world point from the DLT, when it passes the checks above (toleranceI/J: the pixel
// tolerance in each view; minParallaxDeg: the smallest angle between the two rays).
std::optional<Eigen::Vector3d> triangulateKeypointMatch(const Eigen::Matrix3d& K,
                                                        const RigidPose& Ti, cv::Point2d xi,
                                                        double toleranceI, const RigidPose& Tj,
                                                        cv::Point2d xj, double toleranceJ,
                                                        double minParallaxDeg);

}  // namespace reftrack
