#include "engine/reference/TwoViewTriangulator.hpp"

#include <ceres/ceres.h>

#include <cmath>

#include "engine/reference/MultiViewTriangulator.hpp"

namespace reftrack {

TwoViewTriangulator::TwoViewTriangulator(const Eigen::Matrix3d& K, const RigidPose& T_AB)
    : K_(K), T_AB_(T_AB) {}

Eigen::Vector3d TwoViewTriangulator::linear(const Eigen::Vector2d& pA,
                                            const Eigen::Vector2d& pB) const {
  const Eigen::Matrix3d C = K_ * T_AB_.rotation();
  const Eigen::Vector3d& t = T_AB_.translation();
  const Eigen::RowVector3d k1 = K_.row(0), k2 = K_.row(1), k3 = K_.row(2);
  Eigen::Matrix<double, 4, 3> Z;
  Z.row(0) = k1 - pA.x() * k3;
  Z.row(1) = k2 - pA.y() * k3;
  Z.row(2) = C.row(0) - pB.x() * C.row(2);
  Z.row(3) = C.row(1) - pB.y() * C.row(2);
  Eigen::Vector4d z;
  z << 0.0, 0.0, (pB.x() * k3 - k1).dot(t), (pB.y() * k3 - k2).dot(t);
  // Normal equations as in Eq. 9, solved stably by a QR of Z (same minimiser).
  return Z.colPivHouseholderQr().solve(z);
}

Eigen::Vector3d TwoViewTriangulator::refine(const Eigen::Vector2d& pA, const Eigen::Vector2d& pB,
                                            const Eigen::Vector3d& initial) const {
  // Eq. 10 with A as the world frame: the N-view refinement on the two views.
  return MultiViewTriangulator(K_).refine({{RigidPose(), pA}, {T_AB_, pB}}, initial);
}

double TwoViewTriangulator::reprojectionErrorA(const Eigen::Vector3d& P,
                                               const Eigen::Vector2d& pA) const {
  const Eigen::Vector3d q = K_ * P;
  return (q.head<2>() / q.z() - pA).norm();
}

double TwoViewTriangulator::reprojectionErrorB(const Eigen::Vector3d& P,
                                               const Eigen::Vector2d& pB) const {
  const Eigen::Vector3d q = K_ * (T_AB_ * P);
  return (q.head<2>() / q.z() - pB).norm();
}

double TwoViewTriangulator::parallaxAngle(const Eigen::Vector3d& P) const {
  const Eigen::Vector3d rayA = P.normalized();
  const Eigen::Vector3d rayB = (P - T_AB_.inverse().translation()).normalized();
  return std::acos(std::clamp(rayA.dot(rayB), -1.0, 1.0));
}

}  // namespace reftrack
