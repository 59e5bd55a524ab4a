#include "engine/homography/WindowAlignment.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/features/SyntheticImages.hpp"
#include "engine/homography/HomographyDlt.hpp"

using namespace reftrack;

TEST(WindowAlignment, FindsEachWindowWhereTheWarpedReferenceLies) {
  // A tilted, rotated view of a textured reference (noise-free); each point's prediction is
  // 0.8 px off the truth. The windows are sampled exactly through H^-1, so the alignment
  // error is interpolation only: 0.05 px leaves room for the bilinear resampling of the frame.
  const cv::Size size(640, 480);
  const cv::Mat reference = test::texturedImage(size, 41);
  const cv::Matx33d truth = test::tiltedView(size, 25.0, 0.9, 15.0);
  const cv::Mat frame = test::warpedBy(reference, truth);
  CornerParams params;
  params.gridColumns = params.gridRows = 1;
  std::vector<cv::Point2f> exact, predicted;
  for (const Corner& c : CornerDetector(params).detect(reference)) {
    const cv::Point2d q = transferPoint(truth, cv::Point2d(c.position));
    if (q.x < 20 || q.y < 20 || q.x > size.width - 20 || q.y > size.height - 20) continue;
    exact.emplace_back(static_cast<float>(q.x), static_cast<float>(q.y));
    predicted.push_back(exact.back() + cv::Point2f(0.6f, -0.5f));
  }
  ASSERT_GT(exact.size(), 100u);
  // The start H is the truth shifted by the same 0.8 px (a tracked frame's fit a little off): the
  // template around each prediction then holds the frame's content around the exact position,
  // which the alignment must find.
  const cv::Matx33d shifted = cv::Matx33d(1, 0, 0.6, 0, 1, -0.5, 0, 0, 1) * truth;
  const WindowAlignmentResult r = alignWindows(reference, frame, shifted, predicted, 5);
  ASSERT_EQ(r.found.size(), exact.size());
  std::vector<double> errors;
  for (std::size_t i = 0; i < exact.size(); ++i)
    if (r.status[i]) errors.push_back(cv::norm(r.found[i] - exact[i]));
  EXPECT_GT(errors.size(), 0.95 * static_cast<double>(exact.size()));
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.03);
  EXPECT_LT(errors.back(), 0.25);
}

TEST(WindowAlignment, RefusesFlatWindowsAndWindowsOutsideTheFrame) {
  const cv::Mat flat(240, 320, CV_8UC1, cv::Scalar(128));
  const cv::Mat textured = test::texturedImage({320, 240}, 42);
  const WindowAlignmentResult onFlat =
      alignWindows(flat, textured, cv::Matx33d::eye(), {cv::Point2f(160, 120)}, 5);
  EXPECT_EQ(onFlat.status[0], 0);
  const WindowAlignmentResult outside =
      alignWindows(textured, textured, cv::Matx33d::eye(), {cv::Point2f(2, 2)}, 5);
  EXPECT_EQ(outside.status[0], 0);
  EXPECT_THROW(alignWindows(textured, cv::Mat(240, 320, CV_32F), cv::Matx33d::eye(), {}, 5), Error);
  EXPECT_THROW(alignWindows(textured, textured, cv::Matx33d::eye(), {}, 0), Error);
}

TEST(WindowAlignment, RefusesAWindowWhosePreimageCrossesTheReferenceEdgeOnly) {
  // H shifts the reference 10 px right. The template (the window and its 1-pixel border,
  // half + 1 px around q) must lie inside the reference: at q.x = 10 + half + 1.5 its preimage
  // starts 0.5 px inside the reference's left edge, at 10 + half + 0.5 it starts 0.5 px outside
  // (the frame window itself is inside the frame in both cases).
  const int half = 5;
  const cv::Mat textured = test::texturedImage({320, 240}, 43);
  const cv::Matx33d shift(1, 0, 10, 0, 1, 0, 0, 0, 1);
  const cv::Mat frame = test::warpedBy(textured, shift);
  const WindowAlignmentResult r =
      alignWindows(textured, frame, shift,
                   {cv::Point2f(10 + half + 1.5f, 120), cv::Point2f(10 + half + 0.5f, 120)}, half);
  EXPECT_EQ(r.status[0], 1);
  EXPECT_LT(cv::norm(r.found[0] - cv::Point2f(10 + half + 1.5f, 120)), 0.05);
  EXPECT_EQ(r.status[1], 0);
}
