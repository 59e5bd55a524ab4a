#include "engine/reference/TwoViewTriangulator.hpp"

#include <ceres/autodiff_cost_function.h>
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <random>

using namespace reftrack;

namespace {

struct TwoViewSetup {
  Eigen::Matrix3d K;
  RigidPose T_AB;
  TwoViewSetup() {
    K << 600, 0, 319.5, 0, 610, 239.5, 0, 0, 1;
    Vector6d x;
    x << -0.25, 0.03, 0.05, 0.02, -0.22, 0.01;  // ~25 cm baseline, ~13 degrees of rotation
    T_AB = RigidPose::fromVector6(x);
  }
  Eigen::Vector2d projA(const Eigen::Vector3d& P) const {
    const Eigen::Vector3d q = K * P;
    return q.head<2>() / q.z();
  }
  Eigen::Vector2d projB(const Eigen::Vector3d& P) const {
    const Eigen::Vector3d q = K * (T_AB * P);
    return q.head<2>() / q.z();
  }
};

}  // namespace

TEST(TwoViewTriangulator, LinearSolutionIsExactOnExactProjections) {
  const TwoViewSetup s;
  const TwoViewTriangulator tri(s.K, s.T_AB);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(-0.4, 0.4), uz(0.6, 2.5);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d P(ux(rng), ux(rng), uz(rng));
    const Eigen::Vector3d est = tri.linear(s.projA(P), s.projB(P));
    // Exact data: only floating-point round-off remains (1e-9 m = a nanometre at 2.5 m).
    EXPECT_LT((est - P).norm(), 1e-9) << "point " << P.transpose();
  }
}

TEST(TwoViewTriangulator, RefinementReducesErrorUnderPixelNoise) {
  const TwoViewSetup s;
  const TwoViewTriangulator tri(s.K, s.T_AB);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> ux(-0.3, 0.3), uz(0.8, 1.2);
  std::normal_distribution<double> noise(0.0, 0.5);
  double linearReproj = 0, refinedReproj = 0, refined3d = 0;
  const int n = 300;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d P(ux(rng), ux(rng), uz(rng));
    const Eigen::Vector2d pA = s.projA(P) + Eigen::Vector2d(noise(rng), noise(rng));
    const Eigen::Vector2d pB = s.projB(P) + Eigen::Vector2d(noise(rng), noise(rng));
    const Eigen::Vector3d lin = tri.linear(pA, pB);
    const Eigen::Vector3d ref = tri.refine(pA, pB, lin);
    linearReproj +=
        std::pow(tri.reprojectionErrorA(lin, pA), 2) + std::pow(tri.reprojectionErrorB(lin, pB), 2);
    refinedReproj +=
        std::pow(tri.reprojectionErrorA(ref, pA), 2) + std::pow(tri.reprojectionErrorB(ref, pB), 2);
    refined3d += (ref - P).squaredNorm();
  }
  // Eq. 10 minimises exactly the reprojection error, so it can only lower it.
  EXPECT_LT(refinedReproj, linearReproj);
  // Two views with 4 measurements fit 3 unknowns: the expected residual is 1 dof * sigma^2
  // = 0.25 px^2 per point; allow 50% for sampling spread over 300 points.
  EXPECT_LT(refinedReproj / n, 0.25 * 1.5);
  // Depth error at ~1 m with f=600 and a 0.25 m baseline: the disparity carries noise from both
  // views, sqrt(2) * 0.5 px, so sigma_Z ~ Z^2 * 0.71 / (f b) ~ 4.7 mm (Z up to 1.2 m); allow 1.7x.
  EXPECT_LT(std::sqrt(refined3d / n), 0.008);
}

TEST(TwoViewTriangulator, CostJacobianPassesGradientChecker) {
  const TwoViewSetup s;
  ceres::AutoDiffCostFunction<PointReprojectionCost, 2, 3> cost(
      new PointReprojectionCost(s.K, s.T_AB, Eigen::Vector2d(300, 200)));
  ceres::NumericDiffOptions options;
  const std::vector<const ceres::Manifold*>* noManifolds = nullptr;
  ceres::GradientChecker checker(&cost, noManifolds, options);
  double P[3] = {0.1, -0.05, 1.1};
  double* params[] = {P};
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(params, 1e-7, &results)) << results.error_log;
}

TEST(TwoViewTriangulator, ParallaxShrinksWithDistance) {
  const TwoViewSetup s;
  const TwoViewTriangulator tri(s.K, s.T_AB);
  EXPECT_GT(tri.parallaxAngle({0, 0, 1.0}), tri.parallaxAngle({0, 0, 10.0}));
  EXPECT_NEAR(tri.parallaxAngle({0, 0, 1.0}), std::atan2(0.25, 1.0), 0.05);
}
