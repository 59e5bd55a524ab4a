#include "engine/tracking/PoseTracker.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "PlaneWorld.hpp"
#include "engine/core/Error.hpp"
#include "engine/tracking/PredictedOverlayError.hpp"

namespace reftrack {
namespace {

using test::pathPose;
using test::PlaneWorld;

// The tracker follows a 40-frame move of 0.14 m and 6 degrees away from V_A. Errors are measured
// against the exact T_Ak. Tolerances: with ~150 matches of ~0.1-0.2 px noise at ~1 m range the
// pose is determined to well under a millimetre and 0.05 degrees; 2 mm / 0.1 degree leave room
// for the corner detector's viewpoint-dependent bias.
TEST(PoseTracker, TracksAMovingCameraAgainstExactGroundTruth) {
  const PlaneWorld world;
  const ReferenceMap map = world.map();
  ASSERT_GT(map.matches.size(), 80u) << map.cornersA.size() << " " << map.cornersB.size();
  PoseTracker tracker(map, TrackerParams{});
  double maxT = 0, maxR = 0;
  for (int k = 0; k <= 40; ++k) {
    const RigidPose truth = pathPose(k);
    const PoseTrackingResult r = tracker.process(world.render(truth, 100 + k));
    ASSERT_EQ(r.state, TrackingState::Tracking) << "frame " << k << ": " << r.message;
    ASSERT_TRUE(r.T_Ak.has_value());
    maxT = std::max(maxT, RigidPose::translationDistance(*r.T_Ak, truth));
    maxR = std::max(maxR, RigidPose::rotationDistance(*r.T_Ak, truth) * 180.0 / CV_PI);
    EXPECT_GT(r.inliers, 40) << "frame " << k;
  }
  EXPECT_LT(maxT, 0.002);
  EXPECT_LT(maxR, 0.1);
  RecordProperty("max_translation_error_mm", std::to_string(maxT * 1000));
  RecordProperty("max_rotation_error_deg", std::to_string(maxR));
}

// The keypoint measurements (wide_baseline.keypoint_points) join the corners' terms on the same
// move: the references' corners stand in for the keypoint layer (exact 3D points on the plane),
// and the pose stays exact. Measured: 220-odd keypoint terms per frame, max 0.31 mm and 0.016
// degrees (the corners alone, above: 0.87 mm, 0.044 degrees); the tolerances are half the above.
TEST(PoseTracker, KeypointMeasurementsJoinThePoseAndKeepItExact) {
  const PlaneWorld world;
  const ReferenceMap map = world.map();
  TrackerParams params;
  params.wideBaseline.keypointPointsAt320x240 = 100000;
  PoseTracker tracker(map, params);
  std::vector<PoseTracker::VerificationKeypoint> inA, inB;
  const RigidPose AtoWorld = world.T_A.inverse();
  for (const ReferenceCorner& c : map.cornersA)
    inA.push_back({AtoWorld * world.backProject(c.pixel), c.pixel});
  const cv::Matx33d BtoA = world.homography(world.T_AB).inv();
  for (const ReferenceCorner& c : map.cornersB) {
    const cv::Point2d a = test::applyH(BtoA, c.pixel);
    inB.push_back({AtoWorld * world.backProject(
                                  cv::Point2f(static_cast<float>(a.x), static_cast<float>(a.y))),
                   c.pixel});
  }
  tracker.setVerificationKeypoints(std::move(inA), std::move(inB));
  double maxT = 0, maxR = 0;
  int fewest = std::numeric_limits<int>::max();
  for (int k = 0; k <= 40; ++k) {
    const RigidPose truth = pathPose(k);
    const PoseTrackingResult r = tracker.process(world.render(truth, 100 + k));
    ASSERT_EQ(r.state, TrackingState::Tracking) << "frame " << k << ": " << r.message;
    ASSERT_TRUE(r.T_Ak.has_value());
    maxT = std::max(maxT, RigidPose::translationDistance(*r.T_Ak, truth));
    maxR = std::max(maxR, RigidPose::rotationDistance(*r.T_Ak, truth) * 180.0 / CV_PI);
    fewest = std::min(fewest, r.keypointMeasurements);
  }
  EXPECT_GT(fewest, 100);
  EXPECT_LT(maxT, 0.001);
  EXPECT_LT(maxR, 0.05);
  RecordProperty("max_translation_error_mm", std::to_string(maxT * 1000));
  RecordProperty("max_rotation_error_deg", std::to_string(maxR));
  RecordProperty("fewest_keypoint_measurements", std::to_string(fewest));
}

// The stages that run on OpenCV's threads (FAST bands, Harris responses, corner refinement, the
// prediction beside the frame windows, V_A beside V_B, the keypoint alignments and their terms)
// give the same poses to the byte on one thread and on two: each part writes only its own output.
TEST(PoseTracker, ThePosesAreTheSameOnOneThreadAndOnTwo) {
  const PlaneWorld world;
  const ReferenceMap map = world.map();
  TrackerParams params;
  params.wideBaseline.keypointPointsAt320x240 = 100000;
  std::vector<PoseTracker::VerificationKeypoint> inA;
  const RigidPose AtoWorld = world.T_A.inverse();
  for (const ReferenceCorner& c : map.cornersA)
    inA.push_back({AtoWorld * world.backProject(c.pixel), c.pixel});
  const auto track = [&](int threads) {
    const int before = cv::getNumThreads();
    cv::setNumThreads(threads);
    PoseTracker tracker(map, params);
    tracker.setVerificationKeypoints(inA, {});
    std::vector<Vector6d> poses;
    int keypointTerms = 0;
    for (int k = 0; k <= 12; ++k) {
      const PoseTrackingResult r = tracker.process(world.render(pathPose(3 * k), 100 + k));
      poses.push_back(r.T_Ak ? r.T_Ak->toVector6() : Vector6d::Constant(-1.0));
      keypointTerms += r.keypointMeasurements;
    }
    cv::setNumThreads(before);
    return std::pair(poses, keypointTerms);
  };
  const auto [one, termsOne] = track(1);
  const auto [two, termsTwo] = track(2);
  EXPECT_GT(termsOne, 12 * 100);  // the keypoint stage ran on every frame
  EXPECT_EQ(termsOne, termsTwo);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t k = 0; k < one.size(); ++k) {
    EXPECT_NE(one[k][0], -1.0) << "frame " << k << " lost";
    for (int i = 0; i < 6; ++i) EXPECT_EQ(one[k][i], two[k][i]) << "frame " << k << ", entry " << i;
  }
}

TEST(PoseTracker, BlackAndTexturelessFramesAreLostAndRecoveryFollows) {
  const PlaneWorld world;
  PoseTracker tracker(world.map(), TrackerParams{});
  EXPECT_EQ(tracker.process(world.render(pathPose(0), 1)).state, TrackingState::Tracking);
  const PoseTrackingResult black =
      tracker.process(cv::Mat(world.size, CV_8UC3, cv::Scalar(0, 0, 0)));
  EXPECT_EQ(black.state, TrackingState::Lost);
  EXPECT_FALSE(black.worldToCamera.has_value());
  const PoseTrackingResult flat = tracker.process(cv::Mat(world.size, CV_8UC1, cv::Scalar(90)));
  EXPECT_EQ(flat.state, TrackingState::Lost);
  // Back near V_A, the tracker initialises again on its own.
  const PoseTrackingResult back = tracker.process(world.render(pathPose(2), 2));
  EXPECT_EQ(back.state, TrackingState::Tracking) << back.message;
}

// A jump the frame-to-frame step still follows (the camera turned ~5 degrees between two frames:
// the scene moves ~45 px, beyond the wide-baseline search of 20 px at 640x480): the pose is
// matched again around itself on the same frame (PoseTracker step 9a), as exact as in smooth
// tracking. Tolerances as in TracksAMovingCameraAgainstExactGroundTruth (2 mm / 0.1 degree).
TEST(PoseTracker, AJumpIsMatchedAgainAroundItsOwnPose) {
  const PlaneWorld world;
  PoseTracker tracker(world.map(), TrackerParams{});
  for (int k = 0; k <= 4; ++k)
    ASSERT_EQ(tracker.process(world.render(pathPose(k), 300 + k)).state, TrackingState::Tracking);
  const RigidPose turn = RigidPose::fromVector6((Vector6d() << 0, 0, 0, 0.02, 0.08, 0).finished());
  const RigidPose truth = turn * pathPose(5);
  const PoseTrackingResult r = tracker.process(world.render(truth, 305));
  ASSERT_EQ(r.state, TrackingState::Tracking) << r.message;
  EXPECT_NE(r.message.find("after a jump"), std::string::npos) << r.message;
  EXPECT_LT(RigidPose::translationDistance(*r.T_Ak, truth), 0.002);
  EXPECT_LT(RigidPose::rotationDistance(*r.T_Ak, truth) * 180.0 / CV_PI, 0.1);
  // Tracking goes on from it as from any frame.
  const PoseTrackingResult next = tracker.process(world.render(turn * pathPose(6), 306));
  ASSERT_EQ(next.state, TrackingState::Tracking) << next.message;
  EXPECT_EQ(next.message, "tracking");
  EXPECT_LT(RigidPose::translationDistance(*next.T_Ak, turn * pathPose(6)), 0.002);
}

// Worst image displacement (pixels) of the vertices of a 10 cm cube about 1 m in front of camera
// A between the estimated and the true T_Ak: the error a user sees on drawn 3D content.
double cubeVertexErrorPx(const PlaneWorld& world, const RigidPose& estimate,
                         const RigidPose& truth) {
  double worst = 0.0;
  for (int v = 0; v < 8; ++v) {
    const Eigen::Vector3d X(v & 1 ? 0.05 : -0.05, v & 2 ? 0.05 : -0.05, v & 4 ? 1.05 : 0.95);
    const Eigen::Vector3d a = world.K * (estimate * X), b = world.K * (truth * X);
    worst = std::max(worst, (a.hnormalized() - b.hnormalized()).norm());
  }
  return worst;
}

cv::Mat motionBlurred(const cv::Mat& image, int lengthPx) {
  const cv::Mat kernel(1, lengthPx, CV_32F, cv::Scalar(1.0 / lengthPx));
  cv::Mat out;
  cv::filter2D(image, out, -1, kernel, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
  return out;
}

cv::Mat gaussianBlurred(const cv::Mat& image, double sigmaPx) {
  cv::Mat out;
  cv::GaussianBlur(image, out, cv::Size(), sigmaPx, sigmaPx, cv::BORDER_REPLICATE);
  return out;
}

// A tracked sequence, then frames smeared by a 31-px motion kernel or a Gaussian of SD 8 px (the
// image moves ~10x more during the exposure than a corner window is wide): the frame carries no
// reliable support for a pose, so it must be lost with a reason and without a pose, and sharp
// frames afterwards track again.
TEST(PoseTracker, HeavilyBlurredFramesAreLostWithoutAPose) {
  const PlaneWorld world;
  PoseTracker tracker(world.map(), TrackerParams{});
  for (int k = 0; k <= 3; ++k)
    ASSERT_EQ(tracker.process(world.render(pathPose(k), 10 + k)).state, TrackingState::Tracking);
  const std::vector<std::pair<std::string, cv::Mat>> blurred = {
      {"31-px motion blur", motionBlurred(world.render(pathPose(4), 14), 31)},
      {"Gaussian blur SD 8 px", gaussianBlurred(world.render(pathPose(5), 15), 8.0)},
      {"31-px vertical motion blur", motionBlurred(world.render(pathPose(6), 16).t(), 31).t()},
  };
  for (const auto& [what, frame] : blurred) {
    const PoseTrackingResult r = tracker.process(frame);
    EXPECT_EQ(r.state, TrackingState::Lost) << what << ": " << r.message;
    EXPECT_FALSE(r.worldToCamera.has_value()) << what;
    EXPECT_FALSE(r.T_Ak.has_value()) << what;
    EXPECT_FALSE(r.message.empty()) << what;
    RecordProperty(what, r.message);
  }
  // Sharp again near V_A: initialised anew and tracking.
  const PoseTrackingResult back = tracker.process(world.render(pathPose(1), 17));
  EXPECT_EQ(back.state, TrackingState::Tracking) << back.message;
}

// The 31-px motion-blurred frame keeps ~17 inliers whose pose is ~7 px wrong (measured with both
// gates off); the reprojection-RMS gate rejects it only narrowly (3.3 px against 3.0). The
// support check alone, with the RMS gate out of the way, must refuse it: the matches fix the
// scene's image position only to ~1 px (SD), against ~0.1-0.2 px on sharp frames.
TEST(PoseTracker, SupportCheckAloneRefusesAHeavilyBlurredFrame) {
  const PlaneWorld world;
  PoseTrackerLimits limits;
  limits.maxRmsPx = 1e6;
  // Only the strong corners (corners.quality): with the weak ones too, the blurred frame is
  // already refused for too few inliers (measured: 2) before the support check is reached.
  TrackerParams params;
  params.wideBaseline.frameCornerQuality = params.corners.quality;
  PoseTracker tracker(world.map(), params, limits);
  for (int k = 0; k <= 3; ++k) {
    const PoseTrackingResult r = tracker.process(world.render(pathPose(k), 10 + k));
    ASSERT_EQ(r.state, TrackingState::Tracking) << r.message;
    EXPECT_LT(r.supportSdPx, 0.3) << "sharp frame " << k;  // limit 0.5 px at 640x480
  }
  const PoseTrackingResult r = tracker.process(motionBlurred(world.render(pathPose(4), 14), 31));
  EXPECT_EQ(r.state, TrackingState::Lost) << r.message;
  EXPECT_FALSE(r.T_Ak.has_value());
  EXPECT_NE(r.message.find("support"), std::string::npos) << r.message;
  RecordProperty("message", r.message);
}

// Moderate blur within a tracked sequence: every frame either tracks or is lost; a reported pose
// is never wrong. Up to 13-px motion blur and Gaussian SD 2 the cube vertices stay within 1.5 px
// (the product's 95th-percentile target; sharp frames of this scene measure under 0.1 px). The
// heaviest, Gaussian SD 3, may be less exact, but then the tracker must say so: its predicted
// overlay error must be at least a third of the true one (issue 41's "prediction holds" bound),
// and no pose may be 5 px off (the brief's "wrong"). Measured with the outlier gate's refit
// (pose.outlier_gate_sigmas 3): SD 3 worst vertex 1.76 px, predicted 0.89 px (RMS); sharp frames
// predict 0.02-0.06 px, so the prediction does single it out.
TEST(PoseTracker, ModeratelyBlurredFramesTrackAccuratelyOrAreLost) {
  const PlaneWorld world;
  const TrackerParams params;
  PoseTracker tracker(world.map(), params);
  int tracked = 0, frames = 0;
  auto step = [&](int k, const cv::Mat& frame, const std::string& what, bool mustBeExact) {
    const PoseTrackingResult r = tracker.process(frame);
    ++frames;
    if (r.state != TrackingState::Tracking) {
      EXPECT_FALSE(r.T_Ak.has_value()) << what;
      return;
    }
    ++tracked;
    ASSERT_TRUE(r.T_Ak.has_value()) << what;
    ASSERT_TRUE(r.worldToCamera.has_value()) << what;
    const double error = cubeVertexErrorPx(world, *r.T_Ak, pathPose(k));
    EXPECT_LT(error, 5.0) << what << " frame " << k;
    if (mustBeExact) {
      EXPECT_LT(error, 1.5) << what << " frame " << k;
    } else if (error >= 1.5) {
      // The same cube, in world coordinates, for the tracker's own prediction.
      const RigidPose worldToA = r.T_Ak->inverse() * *r.worldToCamera;
      std::vector<Eigen::Vector3d> cube;
      for (int v = 0; v < 8; ++v)
        cube.push_back(worldToA.inverse() * Eigen::Vector3d(v & 1 ? 0.05 : -0.05,
                                                            v & 2 ? 0.05 : -0.05,
                                                            v & 4 ? 1.05 : 0.95));
      const OverlayErrorCheck check =
          checkPredictedOverlayError(PinholeCamera(world.K, world.size), r, cube, params.pose);
      ASSERT_TRUE(check.predictedErrorPx.has_value()) << what;
      EXPECT_LE(error, 3.0 * *check.predictedErrorPx) << what << " frame " << k;
      RecordProperty("heaviest_blur_error_px", std::to_string(error));
      RecordProperty("heaviest_blur_predicted_px", std::to_string(*check.predictedErrorPx));
    }
  };
  int k = 0;
  for (int length : {3, 5, 7, 9, 13}) {
    step(k, world.render(pathPose(k), 30 + k), "sharp", true);
    ++k;
    step(k, motionBlurred(world.render(pathPose(k), 30 + k), length),
         std::to_string(length) + "-px motion blur", true);
    ++k;
  }
  for (double sigma : {0.7, 1.0, 1.5, 2.0, 3.0}) {
    step(k, world.render(pathPose(k), 30 + k), "sharp", true);
    ++k;
    step(k, gaussianBlurred(world.render(pathPose(k), 30 + k), sigma),
         "Gaussian blur SD " + std::to_string(sigma), sigma <= 2.0);
    ++k;
  }
  // The sharp frames and the mildest blurs track: the check must not reject everything.
  EXPECT_GE(tracked, frames / 2) << tracked << " of " << frames;
  RecordProperty("tracked", std::to_string(tracked) + " of " + std::to_string(frames));
}

// A first frame from 1.8 times V_A's distance along its line of sight: matching at the
// reference's scale fails, and the tracker starts once it tries the nearest scale hypothesis
// (at most one per frame, five in turn). From 1.8 m a single textured plane fixes the pose
// less well than from 1 m (its tilt trades against translation): measured 5-10 mm and 0.27
// degree; 15 mm / 0.5 degree bound that, while a wrong scale or wrong matches miss by far more.
TEST(PoseTracker, InitialisesFromAFrameFartherAwayThanTheReference) {
  const PlaneWorld world;
  PoseTracker tracker(world.map(), TrackerParams{});
  const RigidPose truth(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, 0.8));
  int attempts = 0;
  PoseTrackingResult r;
  while (attempts < 5 && r.state != TrackingState::Tracking)
    r = tracker.process(world.render(truth, 40 + attempts++));
  ASSERT_EQ(r.state, TrackingState::Tracking) << r.message;
  ASSERT_TRUE(r.T_Ak.has_value());
  EXPECT_LT(RigidPose::translationDistance(*r.T_Ak, truth), 0.015);
  EXPECT_LT(RigidPose::rotationDistance(*r.T_Ak, truth) * 180.0 / CV_PI, 0.5);
  RecordProperty("frames_to_initialise", std::to_string(attempts));
  RecordProperty("translation_error_mm",
                 std::to_string(RigidPose::translationDistance(*r.T_Ak, truth) * 1000));
  // And it keeps tracking as the camera comes closer.
  for (int k = 1; k <= 10; ++k) {
    const RigidPose nearer(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, 0.8 - 0.02 * k));
    const PoseTrackingResult next = tracker.process(world.render(nearer, 60 + k));
    ASSERT_EQ(next.state, TrackingState::Tracking) << "frame " << k << ": " << next.message;
    EXPECT_LT(RigidPose::translationDistance(*next.T_Ak, nearer), 0.015) << "frame " << k;
  }
}

// A pose off by `centimetres` along (1, -1, 1)/sqrt(3) and `degrees` about (0.3, 1, -0.2).
RigidPose perturbed(const RigidPose& worldToCamera, double centimetres, double degrees) {
  Vector6d d;
  d.head<3>() = Eigen::Vector3d(1, -1, 1).normalized() * centimetres * 0.01;
  d.tail<3>() = Eigen::Vector3d(0.3, 1, -0.2).normalized() * degrees * CV_PI / 180.0;
  return RigidPose::fromVector6(d) * worldToCamera;
}

// seed(): a fresh tracker handed a pose a few centimetres and degrees off the truth, on a frame
// 0.14 m and 6 degrees away from V_A, matches around the seed's projections and reports the exact
// pose. Tolerances as for tracking above (2 mm / 0.1 degree: ~150 matches of ~0.1-0.2 px noise).
TEST(PoseTracker, ASeedNearTheTruthGivesTheExactPose) {
  const PlaneWorld world;
  for (const auto& [cm, deg] : {std::pair{2.0, 1.0}, std::pair{4.0, 3.0}, std::pair{1.0, 5.0}}) {
    PoseTracker tracker(world.map(), TrackerParams{});
    const RigidPose truth = pathPose(40);
    tracker.seed(perturbed(truth * world.T_A, cm, deg));
    const PoseTrackingResult r = tracker.process(world.render(truth, 7));
    ASSERT_EQ(r.state, TrackingState::Tracking) << cm << " cm, " << deg << " deg: " << r.message;
    EXPECT_EQ(r.message, "tracking from a seeded pose");
    ASSERT_TRUE(r.T_Ak.has_value());
    EXPECT_LT(RigidPose::translationDistance(*r.T_Ak, truth), 0.002) << cm << " cm, " << deg;
    EXPECT_LT(RigidPose::rotationDistance(*r.T_Ak, truth) * 180.0 / CV_PI, 0.1)
        << cm << ", " << deg;
    EXPECT_GT(r.inliers, 40);
    // The next frame tracks on as usual (frame-to-frame from the seeded frame).
    const PoseTrackingResult next = tracker.process(world.render(pathPose(41), 8));
    ASSERT_EQ(next.state, TrackingState::Tracking) << next.message;
    EXPECT_EQ(next.message, "tracking");
    EXPECT_LT(RigidPose::translationDistance(*next.T_Ak, pathPose(41)), 0.002);
  }
}

// A seed far from the truth (the wrong place, or the right place looking elsewhere) finds no
// consistent support: the frame is Lost with a reason, never a wrong pose; the same tracker
// seeded well on the next frame tracks again. Also seeding mid-sequence replaces the
// frame-to-frame prediction.
TEST(PoseTracker, ABadlyWrongSeedIsLostNeverAWrongPose) {
  const PlaneWorld world;
  PoseTracker tracker(world.map(), TrackerParams{});
  for (int k = 0; k <= 3; ++k)
    ASSERT_EQ(tracker.process(world.render(pathPose(k), 20 + k)).state, TrackingState::Tracking);
  const std::vector<std::pair<double, double>> wrong = {{30.0, 0.0}, {0.0, 25.0}, {15.0, 15.0}};
  for (std::size_t i = 0; i < wrong.size(); ++i) {
    const auto [cm, deg] = wrong[i];
    const RigidPose truth = pathPose(4 + static_cast<int>(i));
    tracker.seed(perturbed(truth * world.T_A, cm, deg));
    const PoseTrackingResult r = tracker.process(world.render(truth, 30 + static_cast<int>(i)));
    EXPECT_EQ(r.state, TrackingState::Lost) << cm << " cm, " << deg << " deg";
    EXPECT_FALSE(r.worldToCamera.has_value());
    EXPECT_FALSE(r.message.empty());
    RecordProperty("wrong_seed_" + std::to_string(i), r.message);
  }
  tracker.seed(perturbed(pathPose(10) * world.T_A, 1.0, 1.0));
  const PoseTrackingResult r = tracker.process(world.render(pathPose(10), 40));
  ASSERT_EQ(r.state, TrackingState::Tracking) << r.message;
  EXPECT_LT(RigidPose::translationDistance(*r.T_Ak, pathPose(10)), 0.002);
}

// Learned reliability (pose.reliability_prior_observations): every fifth map point moved 4 mm
// along the plane (about 2 px from every view: inside the gate, so kept as an inlier) biases
// every pose that trusts it like the rest. Over the same 60 frames, the tracker that learns each
// point's residuals has a smaller cube error on the last 30 than one that does not. Measured:
// mean worst-vertex error 0.151 px without learning, 0.037 px with it; the bound (half of it)
// leaves room for other noise seeds.
TEST(PoseTracker, LearnedReliabilityDiscountsMapPointsThatMeasureBadly) {
  const PlaneWorld world;
  ReferenceMap map = world.map();
  cv::RNG rng(3);
  int moved = 0;
  for (std::size_t i = 0; i < map.matches.size(); i += 5, ++moved) {
    const Eigen::Vector3d along =
        world.n.cross(Eigen::Vector3d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 0.0))
            .normalized();
    map.matches[i].pointA += 0.004 * along;
  }
  ASSERT_GT(moved, 15);
  const auto meanCubeError = [&](double prior) {
    TrackerParams params;
    params.pose.reliabilityPriorObservations = prior;
    PoseTracker tracker(map, params);
    double sum = 0.0;
    int counted = 0;
    for (int k = 0; k < 60; ++k) {
      const PoseTrackingResult r = tracker.process(world.render(pathPose(k), 200 + k));
      EXPECT_EQ(r.state, TrackingState::Tracking) << "frame " << k << ": " << r.message;
      if (k < 30 || !r.T_Ak) continue;
      sum += cubeVertexErrorPx(world, *r.T_Ak, pathPose(k));
      ++counted;
    }
    return counted > 0 ? sum / counted : INFINITY;
  };
  const double without = meanCubeError(0.0), with = meanCubeError(2.0);
  RecordProperty("cube_error_px_without", std::to_string(without));
  RecordProperty("cube_error_px_with", std::to_string(with));
  EXPECT_LT(with, 0.5 * without) << "without " << without << " px, with " << with << " px";
}

// reset() keeps what the tracker learned of its map (losing track says nothing about the points):
// the same frames after a reset give other poses once the reliability has warmed up.
// forgetLearnedReliability() as well gives the first run's poses bit for bit.
TEST(PoseTracker, ResetKeepsTheLearnedReliabilityAndForgettingRestartsIt) {
  const PlaneWorld world;
  std::vector<cv::Mat> frames;
  for (int k = 0; k < 8; ++k) frames.push_back(world.render(pathPose(k), 300 + k));
  const auto run = [&](PoseTracker& tracker) {
    std::vector<Eigen::Matrix4d> poses;
    for (const cv::Mat& f : frames) {
      const PoseTrackingResult r = tracker.process(f);
      EXPECT_EQ(r.state, TrackingState::Tracking) << r.message;
      poses.push_back(r.T_Ak.value_or(RigidPose()).matrix4());
    }
    return poses;
  };
  PoseTracker tracker(world.map(), TrackerParams{});
  const std::vector<Eigen::Matrix4d> first = run(tracker);
  tracker.reset();
  const std::vector<Eigen::Matrix4d> kept = run(tracker);
  tracker.reset();
  tracker.forgetLearnedReliability();
  const std::vector<Eigen::Matrix4d> forgotten = run(tracker);
  EXPECT_NE(first.back(), kept.back());
  EXPECT_EQ(first, forgotten);
}

TEST(PoseTracker, AFrameOfTheWrongSizeIsAClearError) {
  const PlaneWorld world;
  PoseTracker tracker(world.map(), TrackerParams{});
  try {
    tracker.process(cv::Mat(240, 320, CV_8UC1, cv::Scalar(0)));
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("320x240"), std::string::npos) << e.what();
  }
}

// NaN or infinity in any limit is refused by check() with the field's name, and the tracker
// refuses such limits at construction.
TEST(PoseTrackerLimits, NonFiniteOrOutOfRangeFieldsAreNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<std::pair<std::string, std::function<void(PoseTrackerLimits&)>>> cases = {
      {"min_corners", [](PoseTrackerLimits& l) { l.minCorners = 3; }},
      {"min_inliers", [](PoseTrackerLimits& l) { l.minInliers = 2; }},
      {"gate_px", [&](PoseTrackerLimits& l) { l.gatePx = nan; }},
      {"max_rms_px", [&](PoseTrackerLimits& l) { l.maxRmsPx = inf; }},
      {"max_sigma_translation", [&](PoseTrackerLimits& l) { l.maxSigmaTranslation = nan; }},
      {"ransac_iterations", [](PoseTrackerLimits& l) { l.ransacIterations = 0; }},
      {"min_epipolar_baseline", [&](PoseTrackerLimits& l) { l.minEpipolarBaseline = nan; }},
  };
  for (const auto& [field, mutate] : cases) {
    PoseTrackerLimits l;
    mutate(l);
    try {
      l.check();
      ADD_FAILURE() << field << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  }
  PoseTrackerLimits bad;
  bad.gatePx = nan;
  const PlaneWorld world;
  EXPECT_THROW(PoseTracker(world.map(), TrackerParams{}, bad), Error);
}

}  // namespace
}  // namespace reftrack
