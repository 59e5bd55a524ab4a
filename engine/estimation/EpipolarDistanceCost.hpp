#pragma once
// EpipolarDistanceCost (paper Eq. 3-4, SPEC §2): for a match p_ref <-> p_k between a reference
// view and the current frame, the two perpendicular distances d(p_k, F p_ref) and
// d(p_ref, F^T p_k), with F = K^-T [t]x R K^-1 built from the pose ref -> k. The parameter is
// x_Ak (camera A -> current frame); `refToA` maps the reference camera into camera A (identity
// for V_A, T_AB^-1 for V_B), so ref -> k = T_Ak * refToA. Residuals are divided by `sigma`
// (whitening by the measurement standard deviation, M_meas of Eq. 13). Automatic derivatives:
// the cost is a short chain of smooth operations, and Jets keep it exact and simple.
#include <ceres/ceres.h>

#include <Eigen/Core>

#include "engine/estimation/PoseParameterization.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

struct EpipolarDistanceCost {
  EpipolarDistanceCost(const Eigen::Matrix3d& K, const RigidPose& refToA,
                       const Eigen::Vector2d& pRef, const Eigen::Vector2d& pK, double sigma)
      : Kinv(K.inverse()), refToA(refToA), pRef(pRef), pK(pK), invSigma(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* const x, T* residual) const {
    // Pose ref -> k: R = R_Ak * R_rA, t = R_Ak * t_rA + t_Ak.
    using M3 = Eigen::Matrix<T, 3, 3>;
    using V3 = Eigen::Matrix<T, 3, 1>;
    M3 R;
    for (int c = 0; c < 3; ++c) {
      const T col[3] = {T(refToA.rotation()(0, c)), T(refToA.rotation()(1, c)),
                        T(refToA.rotation()(2, c))};
      T out[3];
      ceres::AngleAxisRotatePoint(x + 3, col, out);
      R(0, c) = out[0];
      R(1, c) = out[1];
      R(2, c) = out[2];
    }
    T t[3];
    const double tr[3] = {refToA.translation().x(), refToA.translation().y(),
                          refToA.translation().z()};
    transformByPoseVector(x, tr, t);
    M3 tx;
    tx << T(0), -t[2], t[1], t[2], T(0), -t[0], -t[1], t[0], T(0);
    const M3 Ki = Kinv.cast<T>();
    const M3 F = Ki.transpose() * tx * R * Ki;
    const V3 a(T(pRef.x()), T(pRef.y()), T(1.0));
    const V3 b(T(pK.x()), T(pK.y()), T(1.0));
    const V3 lineInK = F * a;                // epipolar line of p_ref in the current frame
    const V3 lineInRef = F.transpose() * b;  // epipolar line of p_k in the reference
    const T e = b.dot(lineInK);              // = a^T F^T b, shared numerator
    residual[0] =
        e / ceres::sqrt(lineInK[0] * lineInK[0] + lineInK[1] * lineInK[1] + T(1e-300)) * invSigma;
    residual[1] =
        e / ceres::sqrt(lineInRef[0] * lineInRef[0] + lineInRef[1] * lineInRef[1] + T(1e-300)) *
        invSigma;
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Matrix3d& K, const RigidPose& refToA,
                                     const Eigen::Vector2d& pRef, const Eigen::Vector2d& pK,
                                     double sigma) {
    return new ceres::AutoDiffCostFunction<EpipolarDistanceCost, 2, 6>(
        new EpipolarDistanceCost(K, refToA, pRef, pK, sigma));
  }

  Eigen::Matrix3d Kinv;
  RigidPose refToA;
  Eigen::Vector2d pRef, pK;
  double invSigma;
};

}  // namespace reftrack
