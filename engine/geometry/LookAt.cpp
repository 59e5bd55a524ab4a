#include "engine/geometry/LookAt.hpp"

#include <Eigen/Geometry>

#include "engine/core/Error.hpp"

namespace reftrack {

RigidPose lookAtPose(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                     const Eigen::Vector3d& up) {
  const Eigen::Vector3d forward = target - eye;
  if (!(forward.norm() > 1e-9)) throw Error("lookAtPose: eye and target coincide");
  const Eigen::Vector3d z = forward.normalized();
  const Eigen::Vector3d right = z.cross(up);
  if (!(right.norm() > 1e-9 * up.norm()))
    throw Error("lookAtPose: viewing direction is parallel to the up vector");
  const Eigen::Vector3d x = right.normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d R;
  R.row(0) = x.transpose();
  R.row(1) = y.transpose();
  R.row(2) = z.transpose();
  return RigidPose(R, -R * eye);
}

}  // namespace reftrack
