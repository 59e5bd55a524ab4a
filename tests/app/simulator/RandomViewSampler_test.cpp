#include "app/simulator/RandomViewSampler.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "TestDeskScene.hpp"
#include "app/simulator/ReferencePlacement.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {
constexpr double kDeg = M_PI / 180.0;

std::vector<RigidPose> sixReferences() {
  return placeReferenceViews(6, test::deskScene().referenceEyeA, test::deskScene().referenceEyeB,
                             test::deskScene().contentCentre);
}
}  // namespace

TEST(RandomViewSampler, ViewsLieWithinTheConeDistanceAndRoom) {
  const std::vector<RigidPose> refs = sixReferences();
  RandomViewSampler sampler(refs, test::deskScene().contentCentre, 7);
  double rollLow = 0, rollHigh = 0, angleHigh = 0, ratioLow = 10, ratioHigh = 0;
  std::vector<int> perReference(refs.size(), 0);
  for (int i = 0; i < 500; ++i) {
    const SampledView v = sampler.next();
    ASSERT_GE(v.reference, 0);
    ASSERT_LT(v.reference, 6);
    ++perReference[static_cast<std::size_t>(v.reference)];
    const RigidPose& ref = refs[static_cast<std::size_t>(v.reference)];
    // Measured from the poses themselves, not the sampler's record.
    const Eigen::Vector3d axis = v.worldToCamera.rotation().row(2).transpose();
    const Eigen::Vector3d refAxis = ref.rotation().row(2).transpose();
    const double angle = std::acos(std::clamp(axis.dot(refAxis), -1.0, 1.0));
    EXPECT_LE(angle, 45.0 * kDeg + 1e-9) << i;
    EXPECT_NEAR(angle / kDeg, v.angleDeg, 1e-6) << i;
    const Eigen::Vector3d eye = v.worldToCamera.cameraCentre();
    const double ratio = (eye - test::deskScene().contentCentre).norm() /
                         (ref.cameraCentre() - test::deskScene().contentCentre).norm();
    EXPECT_GE(ratio, 0.5 - 1e-9) << i;
    EXPECT_LE(ratio, 2.0 + 1e-9) << i;
    EXPECT_LT(std::abs(eye.x()), 0.95) << i;
    EXPECT_LT(eye.y(), 0.95) << i;
    EXPECT_GT(eye.z(), 0.35) << i;
    // Looks at the target: it projects onto the optical axis.
    const Eigen::Vector3d inCamera = v.worldToCamera * test::deskScene().contentCentre;
    EXPECT_LT(inCamera.head<2>().norm(), 1e-9) << i;
    EXPECT_GT(inCamera.z(), 0.0) << i;
    rollLow = std::min(rollLow, v.rollDeg);
    rollHigh = std::max(rollHigh, v.rollDeg);
    angleHigh = std::max(angleHigh, angle / kDeg);
    ratioLow = std::min(ratioLow, ratio);
    ratioHigh = std::max(ratioHigh, ratio);
  }
  // 500 draws span the ranges: any roll, up to the cone's edge, near and far (a uniform draw
  // misses the outer 5% of a range in 500 tries with probability < 1e-10; the room cuts some
  // far views, so the far end is asked to reach 1.8).
  EXPECT_LT(rollLow, -170.0);
  EXPECT_GT(rollHigh, 170.0);
  EXPECT_GT(angleHigh, 43.0);
  EXPECT_LT(ratioLow, 0.55);
  EXPECT_GT(ratioHigh, 1.8);
  for (std::size_t r = 0; r < refs.size(); ++r) EXPECT_GT(perReference[r], 30) << r;
}

TEST(RandomViewSampler, DeterministicInTheSeed) {
  RandomViewSampler a(sixReferences(), test::deskScene().contentCentre, 3),
      b(sixReferences(), test::deskScene().contentCentre, 3),
      c(sixReferences(), test::deskScene().contentCentre, 4);
  for (int i = 0; i < 5; ++i) {
    const SampledView va = a.next(), vb = b.next(), vc = c.next();
    EXPECT_EQ(va.worldToCamera.matrix4(), vb.worldToCamera.matrix4());
    EXPECT_GT((va.worldToCamera.matrix4() - vc.worldToCamera.matrix4()).norm(), 1e-3);
  }
}

TEST(RandomViewSampler, RejectsBadInput) {
  EXPECT_THROW(RandomViewSampler({}, test::deskScene().contentCentre, 1), Error);
  RandomViewParams p;
  p.maxAngleDeg = 95;
  EXPECT_THROW(RandomViewSampler(sixReferences(), test::deskScene().contentCentre, 1, p), Error);
  p = {};
  p.minDistanceRatio = 3.0;
  EXPECT_THROW(RandomViewSampler(sixReferences(), test::deskScene().contentCentre, 1, p), Error);
  p = {};
  p.minHeight = 5.0;  // above every possible eye
  RandomViewSampler impossible(sixReferences(), test::deskScene().contentCentre, 1, p);
  EXPECT_THROW(impossible.next(), Error);
}
