#pragma once
// ThreeViewReprojectionCost (paper Eq. 11, SPEC §2): for a three-view match with its reference
// 3D point P (camera A's frame), the residual p_k - proj(K, T_Ak(x), P), divided by `sigma`.
// Automatic derivatives (a rotation and a projection; exact and cheap with Jets).
#include <ceres/ceres.h>

#include <Eigen/Core>
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
struct ThreeViewReprojectionBatchCost {
  struct Match {
    Eigen::Vector3d P;
    Eigen::Vector2d pK;
    double invSigma;
  };
  ThreeViewReprojectionBatchCost(const Eigen::Matrix3d& K, std::vector<Match> matches)
      : K(K), matches(std::move(matches)) {}

  template <typename T>
  bool operator()(const T* const x, T* residual) const {
    for (std::size_t i = 0; i < matches.size(); ++i)
      ThreeViewReprojectionCost::evaluate(x, K, matches[i].P, matches[i].pK, matches[i].invSigma,
                                          residual + 2 * i);
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Matrix3d& K, std::vector<Match> matches) {
    const int residuals = static_cast<int>(2 * matches.size());
    return new ceres::AutoDiffCostFunction<ThreeViewReprojectionBatchCost, ceres::DYNAMIC, 6>(
        new ThreeViewReprojectionBatchCost(K, std::move(matches)), residuals);
  }

  Eigen::Matrix3d K;
  std::vector<Match> matches;
};

}  // namespace reftrack
