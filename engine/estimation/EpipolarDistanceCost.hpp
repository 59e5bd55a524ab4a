#pragma once
// EpipolarDistanceCost (paper Eq. 3-4, SPEC §2): for a match p_ref <-> p_k between a reference
// view and the current frame, the two perpendicular distances d(p_k, F p_ref) and
// d(p_ref, F^T p_k), with F = K^-T [t]x R K^-1 built from the pose ref -> k. The parameter is
// x_Ak (camera A -> current frame); `refToA` maps the reference camera into camera A (identity
// for V_A, T_AB^-1 for V_B), so ref -> k = T_Ak * refToA. Residuals are divided by `sigma`
// (whitening by the measurement standard deviation, M_meas of Eq. 13). Automatic derivatives:
// the cost is a short chain of smooth operations, and Jets keep it exact and simple.
#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <cmath>
#include <utility>
#include <vector>

#include "engine/estimation/PoseParameterization.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

struct EpipolarDistanceCost {
  EpipolarDistanceCost(const Eigen::Matrix3d& K, const RigidPose& refToA,
                       const Eigen::Vector2d& pRef, const Eigen::Vector2d& pK, double sigma)
      : Kinv(K.inverse()), refToA(refToA), pRef(pRef), pK(pK), invSigma(1.0 / sigma) {}

  // F = K^-T [t]x R K^-1 of the pose ref -> k = T_Ak(x) * refToA.
  template <typename T>
  static Eigen::Matrix<T, 3, 3> fundamental(const T* const x, const Eigen::Matrix3d& Kinv,
                                            const RigidPose& refToA) {
    // Pose ref -> k: R = R_Ak * R_rA, t = R_Ak * t_rA + t_Ak.
    using M3 = Eigen::Matrix<T, 3, 3>;
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
    return Ki.transpose() * tx * R * Ki;
  }

  // The two whitened point-to-epipolar-line distances of one match under F.
  template <typename T>
  static void distances(const Eigen::Matrix<T, 3, 3>& F, const Eigen::Vector2d& pRef,
                        const Eigen::Vector2d& pK, double invSigma, T* residual) {
    using V3 = Eigen::Matrix<T, 3, 1>;
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
  }

  template <typename T>
  bool operator()(const T* const x, T* residual) const {
    distances(fundamental(x, Kinv, refToA), pRef, pK, invSigma, residual);
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

// All matches to one reference in one residual block (2 residuals per match): the residuals are
// exactly those of EpipolarDistanceCost, in match order. F and its derivative dF/dx are built
// once per evaluation (with Jets), and each match's derivatives follow from them by the chain
// rule in plain doubles: per match that is a sixth of the Jet arithmetic of the functor (the
// Jets were ~12% of a tracked 1280x720 frame: perf, 6-DOF handheld webcam sequence).
// Checked against numeric derivatives with ceres::GradientChecker (PoseCosts_test).
class EpipolarDistanceBatchCost : public ceres::CostFunction {
 public:
  struct Match {
    Eigen::Vector2d pRef, pK;
    double invSigma;
  };
  EpipolarDistanceBatchCost(const Eigen::Matrix3d& K, const RigidPose& refToA,
                            std::vector<Match> matches)
      : Kinv_(K.inverse()), refToA_(refToA), matches_(std::move(matches)) {
    set_num_residuals(static_cast<int>(2 * matches_.size()));
    mutable_parameter_block_sizes()->push_back(6);
  }

  static ceres::CostFunction* create(const Eigen::Matrix3d& K, const RigidPose& refToA,
                                     std::vector<Match> matches) {
    return new EpipolarDistanceBatchCost(K, refToA, std::move(matches));
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const double* x = parameters[0];
    double* jac = jacobians != nullptr ? jacobians[0] : nullptr;
    Eigen::Matrix3d F;
    Eigen::Matrix3d dF[6];  // dF / dx_k
    if (jac == nullptr) {
      F = EpipolarDistanceCost::fundamental(x, Kinv_, refToA_);
    } else {
      using Jet = ceres::Jet<double, 6>;
      Jet xj[6];
      for (int k = 0; k < 6; ++k) xj[k] = Jet(x[k], k);
      const Eigen::Matrix<Jet, 3, 3> Fj = EpipolarDistanceCost::fundamental(xj, Kinv_, refToA_);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          F(i, j) = Fj(i, j).a;
          for (int k = 0; k < 6; ++k) dF[k](i, j) = Fj(i, j).v[k];
        }
    }
    for (std::size_t m = 0; m < matches_.size(); ++m) {
      const Match& match = matches_[m];
      const Eigen::Vector3d a(match.pRef.x(), match.pRef.y(), 1.0);
      const Eigen::Vector3d b(match.pK.x(), match.pK.y(), 1.0);
      const Eigen::Vector3d l = F * a;              // epipolar line of p_ref in the frame
      const Eigen::Vector3d q = F.transpose() * b;  // epipolar line of p_k in the reference
      const double e = b.dot(l);
      const double nl = std::sqrt(l[0] * l[0] + l[1] * l[1] + 1e-300);
      const double nq = std::sqrt(q[0] * q[0] + q[1] * q[1] + 1e-300);
      const double s = match.invSigma;
      residuals[2 * m] = e / nl * s;
      residuals[2 * m + 1] = e / nq * s;
      if (jac == nullptr) continue;
      double* row0 = jac + 12 * m;
      double* row1 = row0 + 6;
      for (int k = 0; k < 6; ++k) {
        const Eigen::Vector3d dl = dF[k] * a;  // d l / dx_k
        const double dq0 = b[0] * dF[k](0, 0) + b[1] * dF[k](1, 0) + b[2] * dF[k](2, 0);
        const double dq1 = b[0] * dF[k](0, 1) + b[1] * dF[k](1, 1) + b[2] * dF[k](2, 1);
        const double de = b.dot(dl);
        const double dnl = (l[0] * dl[0] + l[1] * dl[1]) / nl;
        const double dnq = (q[0] * dq0 + q[1] * dq1) / nq;
        row0[k] = s * (de / nl - e * dnl / (nl * nl));
        row1[k] = s * (de / nq - e * dnq / (nq * nq));
      }
    }
    return true;
  }

 private:
  Eigen::Matrix3d Kinv_;
  RigidPose refToA_;
  std::vector<Match> matches_;
};

}  // namespace reftrack
