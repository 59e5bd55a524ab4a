#include "engine/estimation/MotionModel.hpp"

#include <Eigen/Cholesky>

#include "engine/core/Error.hpp"

namespace reftrack {

ArMotionModel::ArMotionModel() : weights_{Vector6d::Ones()}, Q_(diagonalNoise(0.001, 0.001)) {}

ArMotionModel::ArMotionModel(std::vector<Vector6d> weights, const Matrix6d& Q)
    : weights_(std::move(weights)), Q_(Q) {
  check();
}

Matrix6d ArMotionModel::diagonalNoise(double translationSigma, double rotationSigma) {
  Matrix6d Q = Matrix6d::Zero();
  Q.diagonal() << Eigen::Vector3d::Constant(translationSigma * translationSigma),
      Eigen::Vector3d::Constant(rotationSigma * rotationSigma);
  return Q;
}

Vector6d ArMotionModel::predict(const std::deque<Vector6d>& history) const {
  if (history.empty()) throw Error("ArMotionModel::predict needs at least one previous state");
  Vector6d x = Vector6d::Zero();
  for (int j = 0; j < order(); ++j) {
    const Vector6d& past = history[std::min<size_t>(j, history.size() - 1)];
    x += weights_[j].cwiseProduct(past);
  }
  return x;
}

void ArMotionModel::check() const {
  if (weights_.empty()) throw Error("motion model: the AR order must be at least 1");
  for (size_t j = 0; j < weights_.size(); ++j)
    if (!weights_[j].allFinite())
      throw Error("motion model: AR weights of lag " + std::to_string(j + 1) + " are not finite");
  if (!Q_.allFinite()) throw Error("motion model: Q contains NaN or infinity");
  if (!Q_.isApprox(Q_.transpose(), 1e-9)) throw Error("motion model: Q must be symmetric");
  if (Eigen::LLT<Matrix6d>(Q_).info() != Eigen::Success)
    throw Error("motion model: Q must be positive definite");
}

}  // namespace reftrack
