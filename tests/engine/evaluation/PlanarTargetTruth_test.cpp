#include "engine/evaluation/PlanarTargetTruth.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <random>

#include "engine/core/Error.hpp"

using namespace reftrack;

namespace {

constexpr double kWidth = 0.105, kHeight = 0.15;  // metres: the synthetic card
constexpr double kPixelsPerMetre = 2000.0;        // of its texture (0.5 mm per texel, ~1 px)

PinholeCamera camera() {
  Eigen::Matrix3d K;
  K << 840, 0, 319.5, 0, 840, 239.5, 0, 0, 1;
  return PinholeCamera(K, {640, 480});
}

// A card with a plain light border (the corners cornerSubPix locks onto) around blurred noise
// (texture for the homography tracker), on a flat dark table.
cv::Mat cardTexture() {
  const cv::Size size(static_cast<int>(std::lround(kWidth * kPixelsPerMetre)),
                      static_cast<int>(std::lround(kHeight * kPixelsPerMetre)));
  cv::Mat noise(size, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 2.0);
  cv::normalize(noise, noise, 40, 200, cv::NORM_MINMAX);
  cv::Mat card(size, CV_8UC1, cv::Scalar(220));
  const int margin = 20;
  noise(cv::Rect(margin, margin, size.width - 2 * margin, size.height - 2 * margin))
      .copyTo(card(cv::Rect(margin, margin, size.width - 2 * margin, size.height - 2 * margin)));
  return card;
}

// World->camera pose of frame k: the camera ~0.4 m in front of the card (world z points into
// the table), drifting sideways and turning a little.
RigidPose framePose(int k) {
  const Eigen::Vector3d centre(0.05 + 0.003 * k, 0.07 - 0.002 * k, -0.4 + 0.002 * k);
  const Eigen::Matrix3d R = rotationFromAxisAngle(Eigen::Vector3d(0.004 * k, -0.006 * k, 0.01));
  return RigidPose(R, -R * centre);
}

// The image of the card under `pose`: texel (u, v) at world (u, v) / kPixelsPerMetre.
cv::Mat render(const cv::Mat& texture, const RigidPose& pose) {
  const Eigen::Matrix3d& R = pose.rotation();
  Eigen::Matrix3d P;
  P << R.col(0), R.col(1), pose.translation();
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  S(0, 0) = S(1, 1) = 1.0 / kPixelsPerMetre;
  // Texel centres at integer coordinates; world (0, 0) is the card's outer corner.
  S(0, 2) = S(1, 2) = 0.5 / kPixelsPerMetre;
  const Eigen::Matrix3d H = camera().K() * P * S;
  cv::Matx33d Hcv;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Hcv(r, c) = H(r, c);
  cv::Mat frame;
  cv::warpPerspective(texture, frame, Hcv, camera().imageSize(), cv::INTER_LINEAR,
                      cv::BORDER_CONSTANT, cv::Scalar(30));
  return frame;
}

TEST(PlanarTargetTruth, RecoversTheCardsPosesAndAspectFromRoughCorners) {
  const cv::Mat texture = cardTexture();
  std::vector<cv::Mat> frames;
  for (int k = 0; k < 12; ++k) frames.push_back(render(texture, framePose(k)));
  const std::vector<Eigen::Vector3d> card = {
      {0, 0, 0}, {kWidth, 0, 0}, {kWidth, kHeight, 0}, {0, kHeight, 0}};
  // Corners "clicked" 1-2 px off their exact image positions.
  std::array<cv::Point2f, 4> clicked;
  const cv::Point2f offsets[4] = {{1.5f, -1.0f}, {-1.0f, 1.5f}, {2.0f, 1.0f}, {-1.5f, -1.5f}};
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d p = camera().project(framePose(0), card[static_cast<std::size_t>(i)]);
    clicked[static_cast<std::size_t>(i)] =
        cv::Point2f(static_cast<float>(p.x()), static_cast<float>(p.y())) + offsets[i];
  }
  const PlanarTargetTruth t = PlanarTargetTruth::follow(frames, camera(), clicked, kWidth);
  // The fit's grid step is 0.005 (measured 1.4300 for 1.4286). Its RMS is IPPE's reprojection
  // of the four corners (measured 0.74 px: IPPE fits the homography, not the pixel residuals).
  EXPECT_NEAR(t.aspectRatio, kHeight / kWidth, 0.01);
  EXPECT_LT(t.aspectRms, 1.0);
  ASSERT_EQ(t.poses.size(), frames.size());
  // The card's centre, carried from frame 0 by the followed homography (the grid truth of
  // bench-real) and projected through the true pose.
  const Eigen::Vector3d centre(0.5 * kWidth, 0.5 * kHeight, 0.0);
  const Eigen::Vector2d centre0 = camera().project(framePose(0), centre);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    ASSERT_TRUE(t.poses[k].has_value()) << "frame " << k << " not followed";
    ASSERT_TRUE(t.homographies[k].has_value());
    const RigidPose truth = framePose(static_cast<int>(k));
    // Corners of the bilinearly rendered card: cornerSubPix finds them to < 0.5 px, in frame 0
    // (then carried by the homography) and in each frame.
    ASSERT_TRUE(t.refinedCorners[k].has_value());
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector2d p = camera().project(truth, card[static_cast<std::size_t>(i)]);
      const cv::Point2f c = (*t.corners[k])[static_cast<std::size_t>(i)];
      EXPECT_LT(std::hypot(c.x - p.x(), c.y - p.y()), 0.5) << "frame " << k << " corner " << i;
      const cv::Point2f r = (*t.refinedCorners[k])[static_cast<std::size_t>(i)];
      EXPECT_LT(std::hypot(r.x - p.x(), r.y - p.y()), 0.5) << "frame " << k << " corner " << i;
    }
    std::vector<cv::Point2f> carried;
    cv::perspectiveTransform(std::vector<cv::Point2f>{cv::Point2f(static_cast<float>(centre0.x()),
                                                                  static_cast<float>(centre0.y()))},
                             carried, cv::Mat(*t.homographies[k]));
    const Eigen::Vector2d c = camera().project(truth, centre);
    // Measured <= 0.017 px: the homography tracker is far more precise than the corners.
    EXPECT_LT(std::hypot(carried[0].x - c.x(), carried[0].y - c.y()), 0.1) << "frame " << k;
    // Four corners of a card seen nearly face-on fix its tilt poorly: corner errors of a few
    // tenths of a pixel tilt the IPPE pose by up to 2 degrees (measured 0.2-2.0 deg, 0.04-2.5
    // mm here), which is why bench-real's primary truth is the homography-carried grid.
    EXPECT_LT(RigidPose::translationDistance(*t.poses[k], truth), 0.004) << "frame " << k;
    EXPECT_LT(RigidPose::rotationDistance(*t.poses[k], truth) * 180.0 / std::numbers::pi, 3.0)
        << "frame " << k;
  }
}

TEST(PlanarTargetTruth, RejectsAnEmptyClipAndABadEdge) {
  const std::array<cv::Point2f, 4> c = {cv::Point2f(10, 10), cv::Point2f(100, 10),
                                        cv::Point2f(100, 100), cv::Point2f(10, 100)};
  EXPECT_THROW(PlanarTargetTruth::follow({}, camera(), c, 0.1), Error);
  const std::vector<cv::Mat> frames = {cv::Mat(480, 640, CV_8UC1, cv::Scalar(0))};
  EXPECT_THROW(PlanarTargetTruth::follow(frames, camera(), c, 0.0), Error);
  const std::vector<cv::Mat> mixed = {frames[0], cv::Mat(240, 320, CV_8UC1, cv::Scalar(0))};
  EXPECT_THROW(PlanarTargetTruth::follow(mixed, camera(), c, 0.1), Error);
}

}  // namespace
