#pragma once
// RigidPose: T = [R | t] mapping points X_to = R * X_from + t (SPEC.md conventions).
// Composition a * b applies b first. The 6-vector form is (t_x, t_y, t_z, r_x, r_y, r_z)
// with r an axis-angle (Rodrigues) vector.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace reftrack {

using Vector6d = Eigen::Matrix<double, 6, 1>;

class RigidPose {
 public:
  RigidPose() = default;  // identity
  RigidPose(const Eigen::Matrix3d& R, const Eigen::Vector3d& t);
  RigidPose(const Eigen::Quaterniond& q, const Eigen::Vector3d& t);

  static RigidPose identity() { return {}; }
  static RigidPose fromVector6(const Vector6d& x);
  // From the 4x4 homogeneous matrix (last row must be 0 0 0 1).
  static RigidPose fromMatrix4(const Eigen::Matrix4d& T);

  const Eigen::Matrix3d& rotation() const { return R_; }
  const Eigen::Vector3d& translation() const { return t_; }
  Eigen::Quaterniond quaternion() const { return Eigen::Quaterniond(R_).normalized(); }
  Vector6d toVector6() const;
  Eigen::Matrix4d matrix4() const;
  Eigen::Matrix<double, 3, 4> matrix3x4() const;

  RigidPose inverse() const;
  RigidPose operator*(const RigidPose& other) const;
  Eigen::Vector3d operator*(const Eigen::Vector3d& X) const { return R_ * X + t_; }
  // For a world->camera pose: the camera centre in world coordinates, -R^T t.
  Eigen::Vector3d cameraCentre() const { return -R_.transpose() * t_; }

  // Rotation angle of R (radians) and translation norm: distances used by the tests.
  static double rotationDistance(const RigidPose& a, const RigidPose& b);
  static double translationDistance(const RigidPose& a, const RigidPose& b);

  bool allFinite() const { return R_.allFinite() && t_.allFinite(); }

 private:
  Eigen::Matrix3d R_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_ = Eigen::Vector3d::Zero();
};

// Axis-angle <-> rotation matrix, consistent with cv::Rodrigues.
Eigen::Matrix3d rotationFromAxisAngle(const Eigen::Vector3d& r);
Eigen::Vector3d axisAngleFromRotation(const Eigen::Matrix3d& R);

}  // namespace reftrack
