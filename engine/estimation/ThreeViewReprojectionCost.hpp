#pragma once
// ThreeViewReprojectionCost (paper Eq. 11, SPEC §2): for a three-view match with its reference
// 3D point P (camera A's frame), the residual p_k - proj(K, T_Ak(x), P), whitened by W (divided
// by `sigma` when isotropic).
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
  // W whitens the residual (W^T W = its inverse covariance; I / sigma for an isotropic one).
  ThreeViewReprojectionCost(const Eigen::Matrix3d& K, const Eigen::Vector3d& P,
                            const Eigen::Vector2d& pK, const Eigen::Matrix2d& W)
      : K(K), P(P), pK(pK), W(W) {}

  template <typename T>
  bool operator()(const T* const x, T* residual) const {
    return evaluate(x, K, P, pK, W, residual);
  }

  template <typename T>
  static bool evaluate(const T* const x, const Eigen::Matrix3d& K, const Eigen::Vector3d& P,
                       const Eigen::Vector2d& pK, const Eigen::Matrix2d& W, T* residual) {
    const double Pa[3] = {P.x(), P.y(), P.z()};
    T Xc[3];
    transformByPoseVector(x, Pa, Xc);
    const T u = (K(0, 0) * Xc[0] + K(0, 1) * Xc[1]) / Xc[2] + K(0, 2);
    const T v = K(1, 1) * Xc[1] / Xc[2] + K(1, 2);
    const T eu = u - pK.x(), ev = v - pK.y();
    residual[0] = W(0, 0) * eu + W(0, 1) * ev;
    residual[1] = W(1, 0) * eu + W(1, 1) * ev;
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Matrix3d& K, const Eigen::Vector3d& P,
                                     const Eigen::Vector2d& pK, const Eigen::Matrix2d& W) {
    return new ceres::AutoDiffCostFunction<ThreeViewReprojectionCost, 2, 6>(
        new ThreeViewReprojectionCost(K, P, pK, W));
  }
  static ceres::CostFunction* create(const Eigen::Matrix3d& K, const Eigen::Vector3d& P,
                                     const Eigen::Vector2d& pK, double sigma) {
    return create(K, P, pK, Eigen::Matrix2d(Eigen::Matrix2d::Identity() / sigma));
  }

  Eigen::Matrix3d K;
  Eigen::Vector3d P;
  Eigen::Vector2d pK;
  Eigen::Matrix2d W;
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
    Eigen::Matrix2d W;  // whitening (I / sigma for an isotropic residual)
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
      const double iz = 1.0 / X.z();
      const double un = fx * X.x() + skew * X.y();
      const double eu = un * iz + cx - match.pK.x(), ev = fy * X.y() * iz + cy - match.pK.y();
      const Eigen::Matrix2d& W = match.W;
      residuals[2 * m] = W(0, 0) * eu + W(0, 1) * ev;
      residuals[2 * m + 1] = W(1, 0) * eu + W(1, 1) * ev;
      if (jac == nullptr) continue;
      // d(u, v) / dX, then whitened by W.
      const double du[3] = {fx * iz, skew * iz, -un * iz * iz};
      const double dv[3] = {0.0, fy * iz, -fy * X.y() * iz * iz};
      double* row0 = jac + 12 * m;
      double* row1 = row0 + 6;
      const auto put = [&](int column, double a, double b) {  // a = du . dX, b = dv . dX
        row0[column] = W(0, 0) * a + W(0, 1) * b;
        row1[column] = W(1, 0) * a + W(1, 1) * b;
      };
      for (int k = 0; k < 3; ++k) put(k, du[k], dv[k]);  // translation: dX / dt = I
      for (int j = 0; j < 3; ++j) {                      // rotation: dX / dr_j = dR_j P
        const Eigen::Vector3d dX = dR[j] * match.P;
        put(3 + j, du[0] * dX.x() + du[1] * dX.y() + du[2] * dX.z(),
            dv[1] * dX.y() + dv[2] * dX.z());
      }
    }
    return true;
  }

 private:
  Eigen::Matrix3d K_;
  std::vector<Match> matches_;
};

}  // namespace reftrack
