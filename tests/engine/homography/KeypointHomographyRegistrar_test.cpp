#include "engine/homography/KeypointHomographyRegistrar.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "engine/features/SyntheticImages.hpp"

using namespace reftrack;

namespace {

HomographyTrackerParams layer(KeypointLayer k) {
  HomographyTrackerParams p;
  p.keypoints = k;
  return p;
}

}  // namespace

TEST(KeypointHomographyRegistrar, FindsAFarViewWithEveryDetector) {
  const cv::Size size(640, 480);
  const cv::Mat reference = test::texturedImage(size, 31);
  const cv::Matx33d truth = test::tiltedView(size, 40.0, 0.7, 130.0);
  const cv::Mat frame = test::withNoise(test::warpedBy(reference, truth), 2.0, 3);
  for (KeypointLayer k : {KeypointLayer::Orb, KeypointLayer::Akaze, KeypointLayer::Sift}) {
    const KeypointHomographyRegistrar registrar(reference, layer(k));
    EXPECT_GT(registrar.referenceKeypoints(), 100) << keypointLayerName(k);
    const KeypointRegistration r = registrar.registerFrame(frame);
    ASSERT_TRUE(r.found) << keypointLayerName(k) << ": " << r.failure;
    EXPECT_GE(r.inliers, 8);
    EXPECT_LE(r.inliers, r.matches);
    // Keypoint positions are good to about a pixel at their scale (up to ~3 px at the coarse
    // octaves a 0.7x view is found on); the homography only has to land within the guided
    // correlation search (+-16 px at 640x480). Measured: 0.3-2.5 px over the three detectors.
    EXPECT_LT(test::cornerError(r.H, truth, size), 8.0) << keypointLayerName(k);
  }
}

TEST(KeypointHomographyRegistrar, DetectingOnADownscaledFrameKeepsFullResolutionPositions) {
  const cv::Size size(640, 480);
  const cv::Mat reference = test::texturedImage(size, 32);
  const cv::Matx33d truth = test::tiltedView(size, 20.0, 1.5, 60.0);
  HomographyTrackerParams p = layer(KeypointLayer::Sift);
  p.keypointDetectScale = 0.5;
  const KeypointRegistration r =
      KeypointHomographyRegistrar(reference, p).registerFrame(test::warpedBy(reference, truth));
  ASSERT_TRUE(r.found) << r.failure;
  // A position error of the half-size frame doubled (plus the pixel-centre shift if it were
  // forgotten: 0.5 px everywhere) — still within a few pixels.
  EXPECT_LT(test::cornerError(r.H, truth, size), 8.0);
}

TEST(KeypointHomographyRegistrar, FindsNothingInAnUnrelatedImage) {
  const cv::Size size(640, 480);
  const KeypointHomographyRegistrar registrar(test::texturedImage(size, 33),
                                              layer(KeypointLayer::Sift));
  const KeypointRegistration r = registrar.registerFrame(test::texturedImage(size, 34));
  EXPECT_FALSE(r.found);
  EXPECT_FALSE(r.failure.empty());
  const KeypointRegistration flat = registrar.registerFrame(cv::Mat(size, CV_8UC1, cv::Scalar(90)));
  EXPECT_FALSE(flat.found);
  EXPECT_EQ(flat.frameKeypoints, 0);
}

TEST(KeypointHomographyRegistrar, RejectsBadInput) {
  const cv::Mat reference = test::texturedImage({320, 240}, 35);
  EXPECT_THROW(KeypointHomographyRegistrar(cv::Mat(), layer(KeypointLayer::Orb)), Error);
  EXPECT_THROW(KeypointHomographyRegistrar(reference, layer(KeypointLayer::None)), Error);
  EXPECT_THROW(KeypointHomographyRegistrar(cv::Mat(240, 320, CV_8UC1, cv::Scalar(7)),
                                           layer(KeypointLayer::Sift)),
               Error);
  HomographyTrackerParams bad = layer(KeypointLayer::Orb);
  bad.keypointRatio = 2.0;
  EXPECT_THROW(KeypointHomographyRegistrar(reference, bad), Error);
  const KeypointHomographyRegistrar registrar(reference, layer(KeypointLayer::Orb));
  EXPECT_THROW(registrar.registerFrame(cv::Mat()), Error);
}
