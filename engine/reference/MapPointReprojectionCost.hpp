#pragma once
// MapPointReprojectionCost: one observation of a map point in one reference for the bundle
// adjustment — residual = proj(K, T(x), X) - p (pixels), x the reference's world->camera pose as
// the 6-vector of SPEC.md (t, axis-angle r), X the point in the world frame, p the observed corner
// undistorted. 2 residuals; parameter blocks: pose (6), point (3). Automatic derivatives.
#include <ceres/ceres.h>

#include <Eigen/Core>

#include "engine/estimation/PoseParameterization.hpp"

namespace reftrack {

struct MapPointReprojectionCost {
  MapPointReprojectionCost(const Eigen::Matrix3d& K, const Eigen::Vector2d& observed)
      : K(K), observed(observed) {}

  template <typename T>
  bool operator()(const T* const pose, const T* const point, T* residual) const {
    T Xc[3];
    transformByPoseVector(pose, point, Xc);
    const T u = (K(0, 0) * Xc[0] + K(0, 1) * Xc[1]) / Xc[2] + K(0, 2);
    const T v = K(1, 1) * Xc[1] / Xc[2] + K(1, 2);
    residual[0] = u - observed.x();
    residual[1] = v - observed.y();
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Matrix3d& K, const Eigen::Vector2d& observed) {
    return new ceres::AutoDiffCostFunction<MapPointReprojectionCost, 2, 6, 3>(
        new MapPointReprojectionCost(K, observed));
  }

  Eigen::Matrix3d K;
  Eigen::Vector2d observed;
};

}  // namespace reftrack
