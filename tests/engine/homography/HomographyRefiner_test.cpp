#include "engine/homography/HomographyRefiner.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"
#include "engine/features/SyntheticImages.hpp"
#include "engine/homography/HomographyDlt.hpp"

using namespace reftrack;

namespace {

// A homography `pixels` away from H at the reference's corners (corner k pushed along a fixed
// direction), for a start that is off by a known amount.
cv::Matx33d perturbed(const cv::Matx33d& H, cv::Size size, double pixels, double angle) {
  std::vector<cv::Point2f> src, dst;
  int k = 0;
  for (const cv::Point2f c :
       {cv::Point2f(0, 0), cv::Point2f(size.width - 1.f, 0), cv::Point2f(0, size.height - 1.f),
        cv::Point2f(size.width - 1.f, size.height - 1.f)}) {
    const cv::Point2d q = transferPoint(H, c);
    const double a = angle + 1.9 * k++;
    src.push_back(c);
    dst.emplace_back(static_cast<float>(q.x + pixels * std::cos(a)),
                     static_cast<float>(q.y + pixels * std::sin(a)));
  }
  return cv::Matx33d(cv::getPerspectiveTransform(src, dst));
}

}  // namespace

TEST(HomographyRefiner, ConvergesToTheTruthFromStartsAFewPixelsOff) {
  // A tilted, zoomed, rotated view with sensor noise; starts 3 px off at the corners in
  // different directions. The warped-reference alignment is exact up to interpolation and the
  // noise (SD 2 grey levels): 0.15 px at the frame corners leaves room for both.
  const cv::Size size(640, 480);
  const cv::Mat world = test::texturedImage(size, 31);
  const cv::Matx33d truth = test::tiltedView(size, 30.0, 0.8, 25.0);
  const cv::Mat frame = test::withNoise(test::warpedBy(world, truth), 2.0, 5);
  const HomographyRefiner refiner(world, 150);
  EXPECT_GT(refiner.points().size(), 300u);  // 150 per 320x240, fewer where the texture is flat
  std::vector<cv::Matx33d> results;
  for (const double angle : {0.0, 2.0, 4.0}) {
    const cv::Matx33d start = perturbed(truth, size, 3.0, angle);
    ASSERT_GT(test::cornerError(start, truth, size), 2.5);
    const RefinedHomography r = refiner.refine(frame, start, 8);
    ASSERT_TRUE(r.success);
    EXPECT_GT(r.inliers, 200);
    EXPECT_LT(test::cornerError(r.H, truth, size), 0.15) << angle;
    results.push_back(r.H);
  }
  // Independent of the start: the three results agree far closer than their error.
  EXPECT_LT(test::cornerError(results[0], results[1], size), 0.02);
  EXPECT_LT(test::cornerError(results[0], results[2], size), 0.02);
}

TEST(HomographyRefiner, AlignsAnHdFrameOnItsPyramidLevelSharedThroughAnImagePyramid) {
  // 1280x720 is aligned on pyramid level 1. Given the frame's ImagePyramid the refiner gives the
  // very same H as given the frame (it builds the same level), and leaves the level built for
  // the pyramid's other users. Start 1 px off (a tracked frame, RefineStart::Close).
  const cv::Size size(1280, 720);
  const cv::Mat world = test::texturedImage(size, 34);
  const cv::Matx33d truth = test::tiltedView(size, 20.0, 0.9, 10.0);
  const cv::Mat frame = test::withNoise(test::warpedBy(world, truth), 2.0, 6);
  const HomographyRefiner refiner(world, 150);
  EXPECT_EQ(refiner.level(), 1);
  const cv::Matx33d start = perturbed(truth, size, 1.0, 0.5);
  const RefinedHomography direct = refiner.refine(frame, start, 8, RefineStart::Close);
  const ImagePyramid pyramid(frame);
  const RefinedHomography shared = refiner.refine(pyramid, start, 8, RefineStart::Close);
  ASSERT_TRUE(direct.success && shared.success);
  EXPECT_EQ(shared.H, direct.H);
  EXPECT_EQ(shared.inliers, direct.inliers);
  // Measured 0.011 px at the frame corners (noise SD 2, bilinear interpolation); 0.05 px leaves
  // a margin of four times that and still fails a refinement that stops a tenth of the start off.
  EXPECT_LT(test::cornerError(shared.H, truth, size), 0.05);
  const uchar* level = pyramid.level(1).data;
  refiner.refine(pyramid, start, 8, RefineStart::Close);
  EXPECT_EQ(pyramid.level(1).data, level);
}

TEST(HomographyRefiner, FailsAndKeepsHWhereThereIsNothingToAlign) {
  const cv::Size size(320, 240);
  const cv::Mat world = test::texturedImage(size, 32);
  const HomographyRefiner refiner(world, 150);
  const cv::Matx33d H = test::tiltedView(size, 10.0, 1.0, 5.0);
  // H maps the whole reference outside the frame: no point to align.
  const cv::Matx33d away = cv::Matx33d(1, 0, 2000, 0, 1, 0, 0, 0, 1) * H;
  const RefinedHomography r = refiner.refine(test::warpedBy(world, H), away, 8);
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.H, away);
}

TEST(HomographyRefiner, RejectsBadInput) {
  const cv::Mat world = test::texturedImage({320, 240}, 33);
  EXPECT_THROW(HomographyRefiner(cv::Mat(), 150), Error);
  EXPECT_THROW(HomographyRefiner(world, 4), Error);
  const HomographyRefiner refiner(world, 150);
  EXPECT_THROW(refiner.refine(cv::Mat(), cv::Matx33d::eye(), 8), Error);
  EXPECT_THROW(refiner.refine(cv::Mat(240, 320, CV_32F, cv::Scalar(0)), cv::Matx33d::eye(), 8),
               Error);
}
