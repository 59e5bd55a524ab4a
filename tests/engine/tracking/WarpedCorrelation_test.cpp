#include "engine/tracking/WarpedCorrelation.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "TrackingTestImages.hpp"
#include "engine/features/CornerDetector.hpp"

namespace reftrack {
namespace {

cv::Mat toFloat(const cv::Mat& m) {
  cv::Mat f;
  m.convertTo(f, CV_32F);
  return f;
}

// Under a 45 degree rotation with 1.4x scale and perspective, plain NCC between corresponding
// windows collapses while Eq. 19, given the true warp, stays near 1 (paper Fig. 11: ~0.95).
TEST(WarpedCorrelation, TrueWarpScoresHighWherePlainCorrelationFails) {
  const cv::Size size(640, 480);
  const cv::Mat frame = test::texturedImage(size, 3);
  const cv::Matx33d G = test::strongWarp(size, 45.0, 1.4);
  const cv::Mat reference = test::warped(frame, G);
  const WarpedCorrelation warpedNcc(toFloat(frame), toFloat(reference), 5);
  const WarpedCorrelation plainNcc(toFloat(frame), toFloat(reference), 5);

  CornerParams cp;
  const std::vector<Corner> corners = CornerDetector(cp).detect(frame);
  ASSERT_GT(corners.size(), 100u);
  std::vector<double> warpedScores, plainScores;
  for (const Corner& c : corners) {
    const cv::Point2d pA = test::applyH(G, c.position);
    if (pA.x < 20 || pA.y < 20 || pA.x > size.width - 20 || pA.y > size.height - 20) continue;
    const auto patch = warpedNcc.framePatch(c.position);
    if (!patch.valid()) continue;
    warpedScores.push_back(warpedNcc.score(patch, G, pA));
    plainScores.push_back(plainNcc.score(patch, cv::Matx33d::eye(), pA));
  }
  ASSERT_GT(warpedScores.size(), 50u);
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  // Bilinear resampling of an anti-aliased texture keeps the true-warp score well above 0.9.
  EXPECT_GT(median(warpedScores), 0.9);
  // Plain NCC of the same windows measured ~0.52 here: the warp, not the texture, is what it
  // misses; require a clear margin rather than an exact value.
  EXPECT_LT(median(plainScores), 0.6);
  EXPECT_GT(median(warpedScores) - median(plainScores), 0.3);
}

TEST(WarpedCorrelation, FlatOrOutsideWindowsHaveNoScore) {
  const cv::Mat flat(100, 100, CV_32F, cv::Scalar(50));
  const WarpedCorrelation c(flat, flat, 5);
  EXPECT_FALSE(c.framePatch({50, 50}).valid());
  EXPECT_FALSE(c.framePatch({2, 50}).valid());
}

}  // namespace
}  // namespace reftrack
