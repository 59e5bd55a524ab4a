#pragma once
// EpipolarPoseFit: how well the given relative pose of two calibrated views explains point
// correspondences between them, beside the relative pose the correspondences themselves give.
// The relative rotation and the direction of the translation (its length is kept: two views fix
// no scale) are fitted from the given pose to the correspondences by Ceres, minimising each
// correspondence's distance to its epipolar line in the second view under a Cauchy loss (scale
// 1 px), so a minority of wrong correspondences barely pulls it. Reported: the median and 90th
// percentile of those distances under the given and under the fitted pose, over the
// correspondences within `inlierPx` of their line under the fitted one.
// Used by EpipolarGuidedMatcher to notice reference poses that disagree with the images (e.g. a
// depth camera's poses given for the colour camera) and to search along the images' own lines.
#include <Eigen/Core>
#include <vector>

#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

struct EpipolarPoseFit {
  RigidPose fitted;  // camera 1 -> camera 2, the given translation's length
  int correspondences = 0;
  int inliers = 0;  // within inlierPx of their epipolar line under the fitted pose
  double givenMedianPx = 0.0, givenP90Px = 0.0;    // inliers' distances under the given pose
  double fittedMedianPx = 0.0, fittedP90Px = 0.0;  // ... and under the fitted one
  double rotationChangeDeg = 0.0;                  // fitted against given
  double translationDirectionChangeDeg = 0.0;
  bool converged = false;
};

// p1, p2: undistorted pixels of the same points in views 1 and 2 (equal sizes, >= 6, or the fit
// returns `given` with zero inliers). given: camera 1 -> camera 2, translation not zero.
EpipolarPoseFit fitEpipolarPose(const Eigen::Matrix3d& K, const RigidPose& given,
                                const std::vector<Eigen::Vector2d>& p1,
                                const std::vector<Eigen::Vector2d>& p2, double inlierPx = 2.0);

}  // namespace reftrack
