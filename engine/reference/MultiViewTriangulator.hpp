#pragma once
// Triangulation of one world point from its pixels in N >= 2 posed views (issue 13): the linear
// DLT (two rows of [x]_x K [R|t] per view, smallest singular vector), then Gauss-Newton on the
// sum of squared reprojection errors (Eq. 10 over all views, Ceres with PointReprojectionCost).
// Pixel coordinates must be undistorted.
#include <Eigen/Core>
#include <vector>

#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

struct PosedPixel {
  RigidPose worldToCamera;
  Eigen::Vector2d pixel;  // undistorted
};

class MultiViewTriangulator {
 public:
  explicit MultiViewTriangulator(const Eigen::Matrix3d& K) : K_(K) {}

  // Linear DLT; NaN when the rays are degenerate (fewer than 2 views or a point at infinity).
  Eigen::Vector3d linear(const std::vector<PosedPixel>& views) const;
  // Minimises the reprojection errors of every view, started from `initial`.
  Eigen::Vector3d refine(const std::vector<PosedPixel>& views,
                         const Eigen::Vector3d& initial) const;
  // Reprojection error (pixels) of X in one view; infinity when X is not in front of it.
  double reprojectionError(const PosedPixel& view, const Eigen::Vector3d& X) const;

 private:
  Eigen::Matrix3d K_;
};

}  // namespace reftrack
