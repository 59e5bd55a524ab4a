#include "engine/homography/WarpedWindowSearch.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"
#include "engine/features/SyntheticImages.hpp"

using namespace reftrack;

TEST(WarpedWindowSearch, FindsShiftedWindowsToSubPixelAccuracy) {
  const cv::Size size(320, 240);
  const cv::Mat reference = test::texturedImage(size, 61);
  // The frame is the reference moved by (2.3, -1.6) px; the prediction says "not moved".
  const cv::Matx33d shift(1, 0, 2.3, 0, 1, -1.6, 0, 0, 1);
  const cv::Mat frame = test::warpedBy(reference, shift);
  // Windows on corners, as the tracker places them (on a straight edge a window slides along it).
  std::vector<cv::Point2f> points;
  cv::goodFeaturesToTrack(reference, points, 60, 0.01, 8, cv::noArray(), 5, true, 0.04);
  const std::vector<cv::Matx22f> identity(points.size(), cv::Matx22f::eye());
  const NccPatches windows = NccPatches::warped(reference, points, identity, 5);
  const std::vector<WindowMatch> found = searchWarpedWindows(frame, windows, points, 4, 0.8);
  ASSERT_GT(found.size(), points.size() / 2);  // windows near the border cannot be searched
  for (const WindowMatch& m : found) {
    const cv::Point2f truth = points[static_cast<size_t>(m.reference)] + cv::Point2f(2.3f, -1.6f);
    // A parabola through the integer NCC peak: bias up to ~0.2 px on this blurred texture.
    EXPECT_LT(cv::norm(m.position - truth), 0.3) << m.reference;
    EXPECT_GE(m.score, 0.8f);
  }
  // A radius smaller than the shift puts the peak on the border of the search square: rejected.
  EXPECT_TRUE(searchWarpedWindows(frame, windows, points, 1, 0.8).empty());
}

TEST(WarpedWindowSearch, RejectsBadInput) {
  const cv::Mat image = test::texturedImage({160, 120}, 62);
  const std::vector<cv::Point2f> points = {{80, 60}};
  const NccPatches windows = NccPatches::square(image, points, 5);
  EXPECT_THROW(searchWarpedWindows(cv::Mat(), windows, points, 3, 0.8), Error);
  EXPECT_THROW(searchWarpedWindows(image, windows, {}, 3, 0.8), Error);
  EXPECT_THROW(searchWarpedWindows(image, windows, points, 0, 0.8), Error);
  cv::Mat colour;
  cv::cvtColor(image, colour, cv::COLOR_GRAY2BGR);
  EXPECT_THROW(searchWarpedWindows(colour, windows, points, 3, 0.8), Error);
}
