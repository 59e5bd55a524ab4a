#include "app/research/homography/VerifierCalibration.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "engine/features/SyntheticImages.hpp"
#include "engine/homography/HomographyDlt.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(VerifierCalibration, DisplacedHomographiesMoveTheFrameCornersByTheOffsets) {
  const cv::Size size(320, 240);
  const cv::Matx33d H(1.1, 0.05, 3, -0.02, 0.95, -4, 1e-4, 2e-4, 1);
  const std::vector<cv::Point2d> offsets = {{3, 4}, {-6, 0}, {0, 10}, {1, -1}};
  const cv::Matx33d D = displacedHomography(H, size, offsets);
  const std::vector<cv::Point2d> corners = {{0, 0}, {319, 0}, {319, 239}, {0, 239}};
  for (size_t i = 0; i < 4; ++i) {
    // A frame corner c shows reference point H^-1 c; the displaced homography puts it at c + d.
    const cv::Point2d moved = transferPoint(D, transferPoint(H.inv(), corners[i]));
    EXPECT_NEAR(moved.x, corners[i].x + offsets[i].x, 1e-6) << i;
    EXPECT_NEAR(moved.y, corners[i].y + offsets[i].y, 1e-6) << i;
  }
  EXPECT_THROW(displacedHomography(H, size, {{1, 1}}), Error);
}

// The check on a synthetic pair: the truth passes, the truth 20 px off at the corners never.
TEST(VerifierCalibration, PassesTheTruthAndRefusesHomographiesFarOff) {
  const cv::Size size(480, 360);
  const cv::Mat reference = test::texturedImage(size, 82);
  const cv::Matx33d truth = test::tiltedView(size, 25.0, 0.9, 30.0);
  const HomographyPair pair{
      "s",  "viewpoint", "t", reference, test::withNoise(test::warpedBy(reference, truth), 2.0, 1),
      truth};
  const std::vector<VerifierPairResult> r = runVerifierCalibration({pair}, {20.0}, 3, 1);
  ASSERT_EQ(r.size(), 1u);
  ASSERT_EQ(r[0].outcomes.size(), 4u);  // the truth, then 3 trials at 20 px
  EXPECT_EQ(r[0].outcomes[0].offsetPx, 0.0);
  EXPECT_TRUE(r[0].outcomes[0].passed) << r[0].outcomes[0].failure;
  for (size_t k = 1; k < 4; ++k) {
    EXPECT_EQ(r[0].outcomes[k].offsetPx, 20.0);
    EXPECT_FALSE(r[0].outcomes[k].passed);
    EXPECT_FALSE(r[0].outcomes[k].failure.empty());
  }
  EXPECT_THROW(runVerifierCalibration({pair}, {5.0}, 0, 1), Error);
}
