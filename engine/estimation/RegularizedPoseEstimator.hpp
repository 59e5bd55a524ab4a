#pragma once
// RegularizedPoseEstimator (paper Sec. 4-5, SPEC §3): the camera-A -> current-frame motion x_Ak
// from two-view epipolar matches to V_A and V_B and three-view reprojections, either by standard
// least squares (Eq. 12) or by the temporally regularised criterion (Eq. 13)
//   e_r(x) = ||z||^2_{M_meas} + alpha ||x - x_pred||^2_{M_prior},  M_prior = Omega_pred^-1,
// both minimised by Levenberg-Marquardt (Ceres). Each result carries Omega = (J^T J)^-1 of the
// whitened residuals at the solution (Gauss-Newton covariance).
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "engine/estimation/MotionModel.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

struct EpipolarMatch {
  Eigen::Vector2d pRef, pK;  // undistorted pixels in the reference and the current frame
  double sigma = 1.0;        // standard deviation of the distance residual (pixels)
};

struct ThreeViewMatch {
  Eigen::Vector3d pointA;  // reference 3D point in camera A's frame
  Eigen::Vector2d pK;      // undistorted pixel in the current frame
  double sigma = 1.0;      // standard deviation of pK (pixels)
  // The residual's whitening W (W^T W = its inverse covariance) when the point's own uncertainty
  // counts too (its triangulation from two references: the covariance sigma^2 I + J Sigma_P
  // J^T); none: 1 / sigma.
  std::optional<Eigen::Matrix2d> whitening{};
  Eigen::Matrix2d whiteningOrScalar() const {
    return whitening ? *whitening : Eigen::Matrix2d(Eigen::Matrix2d::Identity() / sigma);
  }
};

struct PoseMeasurements {
  std::vector<EpipolarMatch> toA, toB;
  std::vector<ThreeViewMatch> threeView;
  std::size_t residualCount() const { return 2 * (toA.size() + toB.size() + threeView.size()); }
};

struct PoseEstimate {
  Vector6d x = Vector6d::Zero();               // x_Ak
  Matrix6d covariance = Matrix6d::Identity();  // Omega_k
  double finalCost = 0.0;                      // e_r at the solution (Ceres' 1/2 factor removed)
  int iterations = 0;
  bool converged = false;
  bool covarianceValid = false;
};

struct PoseSolverOptions {
  int maxIterations = 20;
  // Huber scale on whitened residuals; <= 0 disables (the paper uses plain least squares on
  // RANSAC-cleaned matches).
  double huberScale = 0.0;
};

class RegularizedPoseEstimator {
 public:
  RegularizedPoseEstimator(const Eigen::Matrix3d& K, const RigidPose& T_AB,
                           PoseSolverOptions options = {});

  // Eq. 12: min z^T M_meas z, started at `start`.
  PoseEstimate estimateStandard(const PoseMeasurements& m, const Vector6d& start) const;
  // Eq. 13, started at `start` (x_pred when not given).
  PoseEstimate estimateRegularised(const PoseMeasurements& m, const Vector6d& xPred,
                                   const Matrix6d& omegaPred, double alpha,
                                   const std::optional<Vector6d>& start = std::nullopt) const;

  // Linear start from the 3D-2D pairs (OpenCV PnP: EPnP, then iterative refinement); nullopt
  // with fewer than 6 pairs or a degenerate solution.
  std::optional<Vector6d> linearStart(const std::vector<ThreeViewMatch>& pairs) const;

  const PoseSolverOptions& options() const { return options_; }

 private:
  PoseEstimate solve(const PoseMeasurements& m, const Vector6d& start, const Vector6d* xPred,
                     const Matrix6d* omegaPred, double alpha) const;
  Eigen::Matrix3d K_;
  RigidPose T_AB_;
  PoseSolverOptions options_;
};

}  // namespace reftrack
