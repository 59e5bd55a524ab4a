// Tests for EpipolarDistanceCost and ThreeViewReprojectionCost (header-only cost functors).
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <opencv2/calib3d.hpp>
#include <random>
#include <vector>

#include "engine/estimation/EpipolarDistanceCost.hpp"
#include "engine/estimation/ThreeViewReprojectionCost.hpp"

using namespace reftrack;

namespace {

struct Scene {
  Eigen::Matrix3d K;
  RigidPose T_AB, T_Ak;
  Scene() {
    K << 520, 0, 320, 0, 525, 240, 0, 0, 1;
    T_AB = RigidPose::fromVector6((Vector6d() << -0.25, 0.02, 0.03, 0.03, -0.2, 0.02).finished());
    T_Ak = RigidPose::fromVector6((Vector6d() << 0.08, -0.03, 0.05, -0.06, 0.1, 0.04).finished());
  }
  Eigen::Vector2d project(const RigidPose& T, const Eigen::Vector3d& P) const {
    const Eigen::Vector3d q = K * (T * P);
    return q.head<2>() / q.z();
  }
};

bool gradientsAgree(ceres::CostFunction* cost, const Vector6d& at) {
  std::unique_ptr<ceres::CostFunction> owned(cost);
  ceres::NumericDiffOptions options;
  const std::vector<const ceres::Manifold*>* noManifolds = nullptr;
  ceres::GradientChecker checker(cost, noManifolds, options);
  double x[6];
  for (int i = 0; i < 6; ++i) x[i] = at[i];
  double* params[] = {x};
  ceres::GradientChecker::ProbeResults results;
  const bool ok = checker.Probe(params, 1e-6, &results);
  if (!ok) ADD_FAILURE() << results.error_log;
  return ok;
}

}  // namespace

TEST(EpipolarDistanceCost, ZeroForExactMatchesOfBothReferences) {
  const Scene s;
  const Vector6d x = s.T_Ak.toVector6();
  const Eigen::Vector3d P(0.1, -0.05, 1.1);
  for (const RigidPose& refToA : {RigidPose(), s.T_AB.inverse()}) {
    const Eigen::Vector2d pRef = s.project(refToA.inverse(), P), pK = s.project(s.T_Ak, P);
    EpipolarDistanceCost cost(s.K, refToA, pRef, pK, 1.0);
    double r[2];
    cost(x.data(), r);
    EXPECT_NEAR(r[0], 0.0, 1e-9);
    EXPECT_NEAR(r[1], 0.0, 1e-9);
  }
}

TEST(EpipolarDistanceCost, EqualsPerpendicularDistanceToOpenCvEpiline) {
  const Scene s;
  const Vector6d x = s.T_Ak.toVector6();
  const Eigen::Vector3d P(-0.2, 0.1, 1.4);
  const Eigen::Vector2d pA = s.project(RigidPose(), P);
  const Eigen::Vector2d pK = s.project(s.T_Ak, P) + Eigen::Vector2d(1.5, -2.0);  // off the line
  EpipolarDistanceCost cost(s.K, RigidPose(), pA, pK, 0.5);
  double r[2];
  cost(x.data(), r);
  // Independent: F from the pose, the epiline of p_A in the current frame by OpenCV.
  const Eigen::Matrix3d R = s.T_Ak.rotation();
  const Eigen::Vector3d t = s.T_Ak.translation();
  Eigen::Matrix3d tx;
  tx << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  const Eigen::Matrix3d F = s.K.inverse().transpose() * tx * R * s.K.inverse();
  cv::Matx33d Fcv;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Fcv(i, j) = F(i, j);
  std::vector<cv::Vec3d> lines;
  cv::computeCorrespondEpilines(std::vector<cv::Point2d>{{pA.x(), pA.y()}}, 1, Fcv, lines);
  const double d = lines[0][0] * pK.x() + lines[0][1] * pK.y() + lines[0][2];  // normalised line
  EXPECT_NEAR(std::abs(r[0]) * 0.5, std::abs(d), 1e-9);  // residual is divided by sigma = 0.5
}

TEST(EpipolarDistanceCost, AnalyticJetsMatchNumericDerivatives) {
  const Scene s;
  const Eigen::Vector3d P(0.05, 0.02, 0.9);
  gradientsAgree(
      EpipolarDistanceCost::create(s.K, s.T_AB.inverse(), s.project(s.T_AB, P),
                                   s.project(s.T_Ak, P) + Eigen::Vector2d(0.3, 0.2), 0.4),
      s.T_Ak.toVector6());
}

TEST(ThreeViewReprojectionCost, ZeroAtTruthAndDerivativesCheck) {
  const Scene s;
  const Eigen::Vector3d P(0.1, 0.2, 1.3);
  ThreeViewReprojectionCost cost(s.K, P, s.project(s.T_Ak, P),
                                 Eigen::Matrix2d(Eigen::Matrix2d::Identity() / 0.4));
  double r[2];
  cost(s.T_Ak.toVector6().data(), r);
  EXPECT_NEAR(r[0], 0.0, 1e-9);
  EXPECT_NEAR(r[1], 0.0, 1e-9);
  gradientsAgree(
      ThreeViewReprojectionCost::create(s.K, P, s.project(s.T_Ak, P) + Eigen::Vector2d(1, -1), 0.4),
      s.T_Ak.toVector6());
}

// The batch costs (analytic chain rule through F or R) give the per-match functors' residuals
// and numerically checked derivatives, at a general pose and at one with (almost) no rotation,
// where Ceres switches to its small-angle formulas.
TEST(PoseBatchCosts, ResidualsEqualTheFunctorsAndDerivativesCheck) {
  const Scene s;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.3, 0.3), z(0.7, 1.6), noise(-1.0, 1.0);
  std::vector<EpipolarDistanceBatchCost::Match> epi;
  std::vector<ThreeViewReprojectionBatchCost::Match> tv;
  const RigidPose refToA = s.T_AB.inverse();
  for (int i = 0; i < 12; ++i) {
    const Eigen::Vector3d P(u(rng), u(rng), z(rng));
    const Eigen::Vector2d pK = s.project(s.T_Ak, P) + Eigen::Vector2d(noise(rng), noise(rng));
    epi.push_back({s.project(s.T_AB, P), pK, 1.0 / (0.3 + 0.1 * i)});
    // A general whitening (a point's own uncertainty correlates the residual's two axes).
    Eigen::Matrix2d W;
    W << 1.0 / (0.2 + 0.05 * i), 0.0, 0.3 * noise(rng), 1.0 / (0.3 + 0.02 * i);
    tv.push_back({P, pK, W});
  }
  Vector6d nearIdentity = s.T_Ak.toVector6();
  nearIdentity.tail<3>() << 1e-9, -2e-9, 0.0;
  for (const Vector6d& x : {s.T_Ak.toVector6(), nearIdentity}) {
    std::unique_ptr<ceres::CostFunction> e(EpipolarDistanceBatchCost::create(s.K, refToA, epi));
    std::unique_ptr<ceres::CostFunction> t(ThreeViewReprojectionBatchCost::create(s.K, tv));
    std::vector<double> re(2 * epi.size()), rt(2 * tv.size());
    const double* params[] = {x.data()};
    ASSERT_TRUE(e->Evaluate(params, re.data(), nullptr));
    ASSERT_TRUE(t->Evaluate(params, rt.data(), nullptr));
    for (std::size_t i = 0; i < epi.size(); ++i) {
      double r[2];
      EpipolarDistanceCost(s.K, refToA, epi[i].pRef, epi[i].pK, 1.0 / epi[i].invSigma)(x.data(), r);
      EXPECT_NEAR(re[2 * i], r[0], 1e-9 * (1 + std::abs(r[0])));
      EXPECT_NEAR(re[2 * i + 1], r[1], 1e-9 * (1 + std::abs(r[1])));
      ThreeViewReprojectionCost(s.K, tv[i].P, tv[i].pK, tv[i].W)(x.data(), r);
      EXPECT_NEAR(rt[2 * i], r[0], 1e-9 * (1 + std::abs(r[0])));
      EXPECT_NEAR(rt[2 * i + 1], r[1], 1e-9 * (1 + std::abs(r[1])));
    }
    // The analytic Jacobians equal the automatic ones of the functors (to rounding).
    std::vector<double> je(12 * epi.size()), jt(12 * tv.size());
    double* jacE[] = {je.data()};
    double* jacT[] = {jt.data()};
    ASSERT_TRUE(e->Evaluate(params, re.data(), jacE));
    ASSERT_TRUE(t->Evaluate(params, rt.data(), jacT));
    for (std::size_t i = 0; i < epi.size(); ++i) {
      double r[2], j[12];
      double* jac[] = {j};
      std::unique_ptr<ceres::CostFunction> one(
          EpipolarDistanceCost::create(s.K, refToA, epi[i].pRef, epi[i].pK, 1.0 / epi[i].invSigma));
      ASSERT_TRUE(one->Evaluate(params, r, jac));
      for (int k = 0; k < 12; ++k) EXPECT_NEAR(je[12 * i + k], j[k], 1e-8 * (1 + std::abs(j[k])));
      one.reset(ThreeViewReprojectionCost::create(s.K, tv[i].P, tv[i].pK, tv[i].W));
      ASSERT_TRUE(one->Evaluate(params, r, jac));
      for (int k = 0; k < 12; ++k) EXPECT_NEAR(jt[12 * i + k], j[k], 1e-8 * (1 + std::abs(j[k])));
    }
    EXPECT_TRUE(gradientsAgree(e.release(), x));
    EXPECT_TRUE(gradientsAgree(t.release(), x));
  }
}
