#pragma once
// MotionModelFitter (paper Sec. 5.3, SPEC §3): fits the AR(p) motion model to a recorded
// trajectory. The motion vector of frame k is x_k = vec(T_k T_1^-1), the 6-vector (t, axis-angle)
// of the pose relative to the first frame's camera: the tracker's x_Ak when V_A is the first frame.
// p >= 1: each component's weights by least squares on x_k = sum_j w_j x_{k-j} (no intercept,
// as in the model); Q = sample covariance of the 6-vector residuals. p = 0 ("random walk"):
// weights 1 at lag 1 and Q = covariance of dx_k = x_k - x_{k-1}. Explained variance per
// component = 1 - var(residual) / var(x_k) over the fitted frames. A tiny floor (1e-12) is added
// to Q's diagonal so a component that never moves still gives an invertible Q.
#include <string>
#include <vector>

#include "engine/estimation/MotionModelFile.hpp"
#include "engine/geometry/TumTrajectory.hpp"

namespace reftrack {

class MotionModelFitter {
 public:
  // x_k = vec(T_k T_1^-1) for every pose of the trajectory.
  static std::vector<Vector6d> motionVectors(const TumTrajectory& trajectory);

  // Throws reftrack::Error when the order is outside 0..20 or there are too few states
  // (fewer than order + 8).
  static FittedMotionModel fit(const std::vector<Vector6d>& states, int order);
};

}  // namespace reftrack
