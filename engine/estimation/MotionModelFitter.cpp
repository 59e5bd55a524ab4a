#include "engine/estimation/MotionModelFitter.hpp"

#include <Eigen/QR>

#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

double variance(const Eigen::VectorXd& v) {
  if (v.size() < 2) return 0.0;
  return (v.array() - v.mean()).square().sum() / static_cast<double>(v.size() - 1);
}

Matrix6d covariance(const Eigen::MatrixXd& rows) {  // one sample per row
  const Eigen::RowVectorXd mean = rows.colwise().mean();
  const Eigen::MatrixXd centred = rows.rowwise() - mean;
  return centred.transpose() * centred / static_cast<double>(rows.rows() - 1);
}

}  // namespace

std::vector<Vector6d> MotionModelFitter::motionVectors(const TumTrajectory& trajectory) {
  std::vector<Vector6d> x;
  if (trajectory.poses.empty()) return x;
  const RigidPose firstInverse = trajectory.poses.front().worldToCamera.inverse();
  for (const StampedPose& p : trajectory.poses)
    x.push_back((p.worldToCamera * firstInverse).toVector6());
  return x;
}

FittedMotionModel MotionModelFitter::fit(const std::vector<Vector6d>& states, int order) {
  if (order < 0 || order > 20) throw Error("motion model order must be from 0 to 20");
  const int n = static_cast<int>(states.size());
  const int lags = std::max(order, 1);
  if (n < lags + 8)
    throw Error("fitting an order-" + std::to_string(order) + " motion model needs at least " +
                std::to_string(lags + 8) + " poses, the trajectory has " + std::to_string(n));
  for (int k = 0; k < n; ++k)
    if (!states[k].allFinite())
      throw Error("motion vector of frame " + std::to_string(k + 1) + " is not finite");

  const int rows = n - lags;  // equations k = lags .. n-1
  std::vector<Vector6d> weights(lags, Vector6d::Ones());
  Eigen::MatrixXd residuals(rows, 6);
  Vector6d explained;
  for (int c = 0; c < 6; ++c) {
    Eigen::VectorXd target(rows);
    Eigen::MatrixXd design(rows, lags);
    for (int i = 0; i < rows; ++i) {
      const int k = i + lags;
      target[i] = states[k][c];
      for (int j = 0; j < lags; ++j) design(i, j) = states[k - 1 - j][c];
    }
    Eigen::VectorXd w = Eigen::VectorXd::Ones(lags);
    if (order > 0) w = design.colPivHouseholderQr().solve(target);
    for (int j = 0; j < lags; ++j) weights[j][c] = w[j];
    const Eigen::VectorXd r = target - design * w;
    residuals.col(c) = r;
    const double varX = variance(target);
    explained[c] = varX > 0.0 ? 1.0 - variance(r) / varX : 0.0;
  }
  Matrix6d Q = covariance(residuals);
  Q = 0.5 * (Q + Q.transpose());
  Q.diagonal().array() += 1e-12;

  FittedMotionModel out;
  out.model = ArMotionModel(weights, Q);
  out.randomWalk = order == 0;
  out.explainedVariance = explained;
  out.frameCount = n;
  return out;
}

}  // namespace reftrack
