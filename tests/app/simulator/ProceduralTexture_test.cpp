#include "app/simulator/ProceduralTexture.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {
// 0.4 m of a 1.2 x 0.8 m surface at 0.52 mm texels (the desk's resolution).
const cv::Rect2d kRegion(0.4, 0.2, 0.4, 0.4);
const cv::Size kTexels(768, 768);
}  // namespace

TEST(ProceduralTexture, IsDeterministicInTheSeed) {
  const ProceduralTexture a(3, {1.2, 0.8}), b(3, {1.2, 0.8}), c(4, {1.2, 0.8});
  const cv::Mat ia = a.rasterize(kRegion, kTexels);
  ASSERT_EQ(ia.type(), CV_8UC3);
  ASSERT_EQ(ia.size(), kTexels);
  EXPECT_EQ(cv::norm(ia, b.rasterize(kRegion, kTexels), cv::NORM_INF), 0.0);
  // Another seed is another texture: mean absolute difference of tens of grey levels.
  EXPECT_GT(cv::norm(ia, c.rasterize(kRegion, kTexels), cv::NORM_L1) / (3.0 * ia.total()), 15.0);
}

TEST(ProceduralTexture, NeighbouringTilesJoinWithoutSeams) {
  const ProceduralTexture field(11, {1.2, 0.8});
  const cv::Mat whole = field.rasterize(kRegion, kTexels);
  const cv::Rect2d left(kRegion.x, kRegion.y, kRegion.width / 2, kRegion.height);
  const cv::Rect2d right(kRegion.x + kRegion.width / 2, kRegion.y, kRegion.width / 2,
                         kRegion.height);
  cv::Mat joined;
  cv::hconcat(field.rasterize(left, {384, 768}), field.rasterize(right, {384, 768}), joined);
  cv::Mat diff;
  cv::absdiff(whole, joined, diff);
  // Same texel grid: only OpenCV's 1/32-texel warp quantisation and its fixed-point polygon
  // clipping differ (measured: max 5 grey levels at 3 of 590k texels, mean 5e-5). A seam would
  // differ by tens of levels along a whole column.
  EXPECT_LE(cv::norm(diff, cv::NORM_INF), 8.0);
  EXPECT_LT(cv::mean(diff.reshape(1))[0], 0.01);
}

TEST(ProceduralTexture, IsRichInCornersAndNotRepetitive) {
  const ProceduralTexture field(5, {1.2, 0.8});
  cv::Mat grey;
  cv::cvtColor(field.rasterize({0.2, 0.2, 0.64, 0.48}, {640, 480}), grey, cv::COLOR_BGR2GRAY);
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(grey, corners, 5000, 0.01, 5.0, cv::noArray(), 3, true);
  // Measured 407 Harris corners 5 px apart in this 640x480 view (1 mm texels); a flat or
  // sparse texture gives a few dozen.
  EXPECT_GT(corners.size(), 300u);
  // Correlation aliases where a tracker looks: the 15x15 patch around each of the 200 strongest
  // corners against its +-24 px search window, its own +-3 px excluded. A regular grid would
  // alias nearly every patch; measured: 4 of 200 above 0.9.
  int aliased = 0, tried = 0;
  const cv::Rect inside(24 + 7, 24 + 7, grey.cols - 2 * 31, grey.rows - 2 * 31);
  for (std::size_t i = 0; i < corners.size() && tried < 200; ++i) {
    const cv::Point c(cvRound(corners[i].x), cvRound(corners[i].y));
    if (!inside.contains(c)) continue;
    ++tried;
    const cv::Mat window = grey(cv::Rect(c.x - 31, c.y - 31, 63, 63));
    cv::Mat score;
    cv::matchTemplate(window, grey(cv::Rect(c.x - 7, c.y - 7, 15, 15)), score,
                      cv::TM_CCOEFF_NORMED);
    cv::rectangle(score, cv::Rect(24 - 3, 24 - 3, 7, 7), cv::Scalar(-1), cv::FILLED);
    double best = 0.0;
    cv::minMaxLoc(score, nullptr, &best);
    if (best > 0.9) ++aliased;
  }
  EXPECT_EQ(tried, 200);
  EXPECT_LE(aliased, 10) << "corner patches with a > 0.9 correlation alias nearby";
}

TEST(ProceduralTexture, RejectsBadInput) {
  EXPECT_THROW(ProceduralTexture(1, {0.0, 1.0}), Error);
  TextureStyle style;
  style.minShapeMetres = 0.2;
  style.maxShapeMetres = 0.1;
  EXPECT_THROW(ProceduralTexture(1, {1.0, 1.0}, style), Error);
  const ProceduralTexture field(1, {1.0, 1.0});
  EXPECT_THROW(field.rasterize({0, 0, 1, 1}, {0, 10}), Error);
  EXPECT_THROW(field.rasterize({0, 0, 0, 1}, {10, 10}), Error);
}
