#include "engine/homography/HomographyDlt.hpp"

#include <gtest/gtest.h>

using namespace reftrack;

namespace {
const cv::Matx33d kTruth(1.1, 0.05, 12.0, -0.03, 0.95, -7.0, 2e-4, -1e-4, 1.0);
}

TEST(HomographyDlt, ExactFromFourAndFromMany) {
  std::vector<cv::Point2f> src, dst;
  cv::RNG rng(1);
  for (int i = 0; i < 40; ++i) {
    const cv::Point2f p(rng.uniform(0.f, 320.f), rng.uniform(0.f, 240.f));
    const cv::Point2d q = transferPoint(kTruth, p);
    src.push_back(p);
    dst.emplace_back(static_cast<float>(q.x), static_cast<float>(q.y));
  }
  for (const std::vector<int>& subset : {std::vector<int>{0, 1, 2, 3}, std::vector<int>{}}) {
    const auto H = homographyDlt(src, dst, subset);
    ASSERT_TRUE(H);
    EXPECT_NEAR((*H)(2, 2), 1.0, 1e-12);
    // Float point storage limits the match to ~1e-4 px; the entries then agree to ~1e-5.
    for (size_t i = 0; i < src.size(); ++i) EXPECT_LT(transferError(*H, src[i], dst[i]), 2e-3);
  }
}

TEST(HomographyDlt, DegenerateInputGivesNothing) {
  const std::vector<cv::Point2f> line = {{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 4}};
  EXPECT_FALSE(homographyDlt(line, line));
  const std::vector<cv::Point2f> three = {{0, 0}, {10, 0}, {0, 10}};
  EXPECT_FALSE(homographyDlt(three, three));
  std::vector<cv::Point2f> nan = {{0, 0}, {10, 0}, {0, 10}, {NAN, 5}};
  EXPECT_FALSE(homographyDlt(nan, nan));
  EXPECT_FALSE(homographyDlt(three, line));
}

TEST(HomographyDlt, NormalisingTransformCentresAndScales) {
  const std::vector<cv::Point2f> pts = {{10, 10}, {30, 10}, {30, 50}, {10, 50}};
  const cv::Matx33d T = normalisingTransform(pts);
  double cx = 0, cy = 0, d = 0;
  for (const auto& p : pts) {
    const cv::Point2d q = transferPoint(T, p);
    cx += q.x / 4;
    cy += q.y / 4;
    d += std::hypot(q.x, q.y) / 4;
  }
  EXPECT_NEAR(cx, 0, 1e-12);
  EXPECT_NEAR(cy, 0, 1e-12);
  EXPECT_NEAR(d, std::sqrt(2.0), 1e-12);
}
