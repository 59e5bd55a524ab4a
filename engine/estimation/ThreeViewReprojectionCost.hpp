#pragma once
// ThreeViewReprojectionCost (paper Eq. 11, SPEC §2): for a three-view match with its reference
// 3D point P (camera A's frame), the residual p_k - proj(K, T_Ak(x), P), divided by `sigma`.
// Automatic derivatives (a rotation and a projection; exact and cheap with Jets).
#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <cmath>
#include <utility>
#include <vector>

#include "engine/estimation/PoseParameterization.hpp"

namespace reftrack {

struct ThreeViewReprojectionCost {
  ThreeViewReprojectionCost(const Eigen::Matrix3d& K, const Eigen::Vector3d& P,
                            const Eigen::Vector2d& pK, double sigma)
      : K(K), P(P), pK(pK), invSigma(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* const x, T* residual) const {
    return evaluate(x, K, P, pK, invSigma, residual);
  }

  template <typename T>
  static bool evaluate(const T* const x, const Eigen::Matrix3d& K, const Eigen::Vector3d& P,
                       const Eigen::Vector2d& pK, double invSigma, T* residual) {
    const double Pa[3] = {P.x(), P.y(), P.z()};
    T Xc[3];
    transformByPoseVector(x, Pa, Xc);
    const T u = (K(0, 0) * Xc[0] + K(0, 1) * Xc[1]) / Xc[2] + K(0, 2);
    const T v = K(1, 1) * Xc[1] / Xc[2] + K(1, 2);
    residual[0] = (u - pK.x()) * invSigma;
    residual[1] = (v - pK.y()) * invSigma;
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Matrix3d& K, const Eigen::Vector3d& P,
                                     const Eigen::Vector2d& pK, double sigma) {
    return new ceres::AutoDiffCostFunction<ThreeViewReprojectionCost, 2, 6>(
        new ThreeViewReprojectionCost(K, P, pK, sigma));
  }

  Eigen::Matrix3d K;
  Eigen::Vector3d P;
  Eigen::Vector2d pK;
  double invSigma;
};

// All three-view matches in one residual block (2 residuals per match, same values and order as
// ThreeViewReprojectionCost): one block instead of hundreds keeps the solver's overhead small.
// R(x) and its derivatives are built once per evaluation (with Jets) and each match's
// derivatives follow by the chain rule in plain doubles, instead of rotating every point with
// Jets (a sine and cosine per point). Checked with ceres::GradientChecker (PoseCosts_test).
class ThreeViewReprojectionBatchCost : public ceres::CostFunction {
 public:
  struct Match {
    Eigen::Vector3d P;
    Eigen::Vector2d pK;
    double invSigma;
  };
  ThreeViewReprojectionBatchCost(const Eigen::Matrix3d& K, std::vector<Match> matches)
      : K_(K), matches_(std::move(matches)) {
    set_num_residuals(static_cast<int>(2 * matches_.size()));
    mutable_parameter_block_sizes()->push_back(6);
  }

  static ceres::CostFunction* create(const Eigen::Matrix3d& K, std::vector<Match> matches) {
    return new ThreeViewReprojectionBatchCost(K, std::move(matches));
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const double* x = parameters[0];
    double* jac = jacobians != nullptr ? jacobians[0] : nullptr;
    // R(r) row-major and dR / dr_j, from Jets in the rotation's three parameters.
    using Jet = ceres::Jet<double, 3>;
    const Jet r[3] = {Jet(x[3], 0), Jet(x[4], 1), Jet(x[5], 2)};
    Jet Rj[9];
    ceres::AngleAxisToRotationMatrix(r, ceres::RowMajorAdapter3x3(Rj));
    Eigen::Matrix3d R, dR[3];
    for (int i = 0; i < 9; ++i) {
      R(i / 3, i % 3) = Rj[i].a;
      for (int j = 0; j < 3; ++j) dR[j](i / 3, i % 3) = Rj[i].v[j];
    }
    const Eigen::Vector3d t(x[0], x[1], x[2]);
    const double fx = K_(0, 0), skew = K_(0, 1), cx = K_(0, 2), fy = K_(1, 1), cy = K_(1, 2);
    for (std::size_t m = 0; m < matches_.size(); ++m) {
      const Match& match = matches_[m];
      const Eigen::Vector3d X = R * match.P + t;
      const double iz = 1.0 / X.z(), s = match.invSigma;
      const double un = fx * X.x() + skew * X.y();
      residuals[2 * m] = (un * iz + cx - match.pK.x()) * s;
      residuals[2 * m + 1] = (fy * X.y() * iz + cy - match.pK.y()) * s;
      if (jac == nullptr) continue;
      // d(u, v) / dX, whitened.
      const double du[3] = {fx * iz * s, skew * iz * s, -un * iz * iz * s};
      const double dv[3] = {0.0, fy * iz * s, -fy * X.y() * iz * iz * s};
      double* row0 = jac + 12 * m;
      double* row1 = row0 + 6;
      for (int k = 0; k < 3; ++k) {  // translation: dX / dt = I
        row0[k] = du[k];
        row1[k] = dv[k];
      }
      for (int j = 0; j < 3; ++j) {  // rotation: dX / dr_j = dR_j P
        const Eigen::Vector3d dX = dR[j] * match.P;
        row0[3 + j] = du[0] * dX.x() + du[1] * dX.y() + du[2] * dX.z();
        row1[3 + j] = dv[1] * dX.y() + dv[2] * dX.z();
      }
    }
    return true;
  }

 private:
  Eigen::Matrix3d K_;
  std::vector<Match> matches_;
};

}  // namespace reftrack
