#include "engine/geometry/RigidPose.hpp"

#include <cmath>

#include "engine/core/Error.hpp"

namespace reftrack {

RigidPose::RigidPose(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) : R_(R), t_(t) {}

RigidPose::RigidPose(const Eigen::Quaterniond& q, const Eigen::Vector3d& t)
    : R_(q.normalized().toRotationMatrix()), t_(t) {}

RigidPose RigidPose::fromVector6(const Vector6d& x) {
  return {rotationFromAxisAngle(x.tail<3>()), x.head<3>()};
}

RigidPose RigidPose::fromMatrix4(const Eigen::Matrix4d& T) {
  if (!(T.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).isZero(1e-9))
    throw Error("RigidPose: the last row of a 4x4 pose must be [0 0 0 1]");
  return {T.topLeftCorner<3, 3>(), T.topRightCorner<3, 1>()};
}

Vector6d RigidPose::toVector6() const {
  Vector6d x;
  x.head<3>() = t_;
  x.tail<3>() = axisAngleFromRotation(R_);
  return x;
}

Eigen::Matrix4d RigidPose::matrix4() const {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = R_;
  T.topRightCorner<3, 1>() = t_;
  return T;
}

Eigen::Matrix<double, 3, 4> RigidPose::matrix3x4() const {
  Eigen::Matrix<double, 3, 4> P;
  P << R_, t_;
  return P;
}

RigidPose RigidPose::inverse() const {
  Eigen::Matrix3d Rt = R_.transpose();
  return {Rt, -Rt * t_};
}

RigidPose RigidPose::operator*(const RigidPose& other) const {
  return {R_ * other.R_, R_ * other.t_ + t_};
}

double RigidPose::rotationDistance(const RigidPose& a, const RigidPose& b) {
  return axisAngleFromRotation(a.R_.transpose() * b.R_).norm();
}

double RigidPose::translationDistance(const RigidPose& a, const RigidPose& b) {
  return (a.t_ - b.t_).norm();
}

Eigen::Matrix3d rotationFromAxisAngle(const Eigen::Vector3d& r) {
  const double angle = r.norm();
  if (angle < 1e-15) {
    // First-order expansion keeps the map smooth at zero.
    Eigen::Matrix3d K;
    K << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
    return Eigen::Matrix3d::Identity() + K;
  }
  return Eigen::AngleAxisd(angle, r / angle).toRotationMatrix();
}

Eigen::Vector3d axisAngleFromRotation(const Eigen::Matrix3d& R) {
  Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

}  // namespace reftrack
