#pragma once
// ArMotionModel (paper Sec. 5.1-5.3, SPEC §3): an AR(p) model of the motion vector,
// x_k = Q_1 x_{k-1} + ... + Q_p x_{k-p} + e_k, each Q_j diagonal (one weight per component),
// with the process-noise covariance Q of e_k. Default AR(1) with weights 1: x_pred = x_{k-1}.
#include <Eigen/Core>
#include <deque>
#include <vector>

#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

class ArMotionModel {
 public:
  ArMotionModel();  // AR(1), weights 1, Q = diag(1 mm, 1 mrad)^2 per frame
  // weights[j] holds the 6 diagonal entries of Q_{j+1}; Q is the 6x6 noise covariance.
  ArMotionModel(std::vector<Vector6d> weights, const Matrix6d& Q);

  int order() const { return static_cast<int>(weights_.size()); }
  const std::vector<Vector6d>& weights() const { return weights_; }
  const Matrix6d& processNoise() const { return Q_; }
  // Diagonal Q from per-frame standard deviations of translation (m) and rotation (rad).
  static Matrix6d diagonalNoise(double translationSigma, double rotationSigma);

  // Prediction from the most recent states (history.front() = x_{k-1}); a shorter history
  // than the order uses the oldest state for the missing lags.
  Vector6d predict(const std::deque<Vector6d>& history) const;

  // Throws reftrack::Error naming a bad entry (non-finite, Q not symmetric positive definite).
  void check() const;

 private:
  std::vector<Vector6d> weights_;
  Matrix6d Q_;
};

}  // namespace reftrack
