#pragma once
// The 6-vector motion parameterisation x = (t_x, t_y, t_z, r_x, r_y, r_z) of SPEC.md (r an
// axis-angle vector), usable with Ceres Jets: transform a point by the pose x.
#include <ceres/rotation.h>

namespace reftrack {

// Xout = R(x) * X + t(x).
template <typename T, typename P>
inline void transformByPoseVector(const T* x, const P* X, T* Xout) {
  const T Xt[3] = {T(X[0]), T(X[1]), T(X[2])};
  ceres::AngleAxisRotatePoint(x + 3, Xt, Xout);
  Xout[0] += x[0];
  Xout[1] += x[1];
  Xout[2] += x[2];
}

}  // namespace reftrack
