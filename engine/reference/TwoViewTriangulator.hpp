#pragma once
// Two-view triangulation of reference matches (paper Sec. 3.3, SPEC §1): the linear solution of
// Eq. 9 for a point P in camera A's frame from ~p_A ~ K[I|0]P and ~p_B ~ K[R_AB|t_AB]P, and the
// non-linear refinement of Eq. 10 (sum of both squared reprojection errors) with Ceres.
// Pixel coordinates must be undistorted.
#include <Eigen/Core>

#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

class TwoViewTriangulator {
 public:
  // T_AB maps camera-A points to camera B.
  TwoViewTriangulator(const Eigen::Matrix3d& K, const RigidPose& T_AB);

  // Eq. 9: P = (Z^T Z)^-1 Z^T z.
  Eigen::Vector3d linear(const Eigen::Vector2d& pA, const Eigen::Vector2d& pB) const;
  // Eq. 10, started from `initial`; returns the refined point.
  Eigen::Vector3d refine(const Eigen::Vector2d& pA, const Eigen::Vector2d& pB,
                         const Eigen::Vector3d& initial) const;

  // Reprojection error (pixels) of P in A and in B.
  double reprojectionErrorA(const Eigen::Vector3d& P, const Eigen::Vector2d& pA) const;
  double reprojectionErrorB(const Eigen::Vector3d& P, const Eigen::Vector2d& pB) const;
  // Angle (radians) between the two viewing rays of P: small angles mean little parallax.
  double parallaxAngle(const Eigen::Vector3d& P) const;

 private:
  Eigen::Matrix3d K_;
  RigidPose T_AB_;
};

// Ceres cost of Eq. 10 for one view: residual = p - proj(K, T, P), 2 residuals, 3 parameters.
struct PointReprojectionCost {
  PointReprojectionCost(const Eigen::Matrix3d& K, const RigidPose& T, const Eigen::Vector2d& p)
      : K(K), T(T), p(p) {}
  template <typename S>
  bool operator()(const S* const P, S* residual) const {
    const Eigen::Matrix<S, 3, 1> X(P[0], P[1], P[2]);
    const Eigen::Matrix<S, 3, 1> Xc = T.rotation().cast<S>() * X + T.translation().cast<S>();
    const Eigen::Matrix<S, 3, 1> q = K.cast<S>() * Xc;
    residual[0] = q[0] / q[2] - S(p.x());
    residual[1] = q[1] / q[2] - S(p.y());
    return true;
  }
  Eigen::Matrix3d K;
  RigidPose T;
  Eigen::Vector2d p;
};

}  // namespace reftrack
