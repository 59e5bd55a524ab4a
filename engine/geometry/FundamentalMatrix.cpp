#include "engine/geometry/FundamentalMatrix.hpp"

#include <Eigen/Dense>

namespace reftrack {

Eigen::Matrix3d skewSymmetric(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Matrix3d fundamentalMatrix(const Eigen::Matrix3d& K, const RigidPose& oneToTwo) {
  const Eigen::Matrix3d Kinv = K.inverse();
  return Kinv.transpose() * skewSymmetric(oneToTwo.translation()) * oneToTwo.rotation() * Kinv;
}

}  // namespace reftrack
