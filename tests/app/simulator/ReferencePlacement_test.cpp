#include "app/simulator/ReferencePlacement.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "TestDeskScene.hpp"
#include "app/simulator/WalkaroundArc.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/LookAt.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {
constexpr double kDeg = M_PI / 180.0;
}  // namespace

TEST(ReferencePlacement, FirstTwoAreAAndBThenBothSidesOfTheArcOutwards) {
  const std::vector<RigidPose> two =
      placeReferenceViews(2, test::deskScene().referenceEyeA, test::deskScene().referenceEyeB,
                          test::deskScene().contentCentre);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_LT((two[0].matrix4() -
             lookAtPose(test::deskScene().referenceEyeA, test::deskScene().contentCentre).matrix4())
                .norm(),
            1e-12);
  EXPECT_LT((two[1].matrix4() -
             lookAtPose(test::deskScene().referenceEyeB, test::deskScene().contentCentre).matrix4())
                .norm(),
            1e-12);

  const std::vector<RigidPose> six =
      placeReferenceViews(6, test::deskScene().referenceEyeA, test::deskScene().referenceEyeB,
                          test::deskScene().contentCentre);
  ASSERT_EQ(six.size(), 6u);
  EXPECT_LT((six[1].matrix4() - two[1].matrix4()).norm(), 1e-12);
  // Views 2..5 at -40, +40, -65, +65 deg (15 + 50 i / 2 on each side).
  const double expected[] = {-40.0, 40.0, -65.0, 65.0};
  for (int i = 2; i < 6; ++i) {
    const ArcPosition p =
        WalkaroundArc::positionOf(six[i].cameraCentre(), test::deskScene().contentCentre);
    EXPECT_NEAR(p.azimuthRad / kDeg, expected[i - 2], 1e-9) << i;
    // Every view looks at the target: it projects onto the optical axis.
    const Eigen::Vector3d inCamera = six[i] * test::deskScene().contentCentre;
    EXPECT_LT(std::hypot(inCamera.x(), inCamera.y()), 1e-9) << i;
    EXPECT_GT(inCamera.z(), 0.5) << i;
  }
  // No two views coincide.
  for (int i = 0; i < 6; ++i)
    for (int j = i + 1; j < 6; ++j)
      EXPECT_GT((six[i].cameraCentre() - six[j].cameraCentre()).norm(), 0.2) << i << " " << j;
  EXPECT_THROW(
      placeReferenceViews(1, test::deskScene().referenceEyeA, test::deskScene().referenceEyeB,
                          test::deskScene().contentCentre),
      Error);
}
