#include "engine/api/Tracker.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <set>

#include "TestPaths.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/SyntheticImages.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/relocalisation/Relocaliser.hpp"
#include "engine/tracking/MultiReferenceTracker.hpp"
#include "engine/tracking/PlaneMultiWorld.hpp"
#include "engine/tracking/PredictedOverlayError.hpp"

namespace reftrack {
namespace {

using test::PlaneMultiWorld;
using test::rotationErrorDeg;
using test::translationErrorMm;

// Four references 0.2 m apart along x looking at a textured plane (exact ground truth), with
// the relocaliser's keypoint layer, saved as a map folder the way `reftrack prepare` leaves one.
struct SavedMap {
  PlaneMultiWorld world{{-0.3, -0.1, 0.1, 0.3}};
  std::filesystem::path folder;
  explicit SavedMap(const std::string& name) : folder(test::freshTempDir(name) / "map") {
    MultiReferenceMap map = world.map();
    buildReferenceKeypoints(map, RelocalisationParams{});
    map.save(folder);
  }
};

// A path across three pairs of references: every frame tracked from the saved map, each pose
// within MultiReferenceTracker_test's tolerances of the exact ground truth (2 mm / 0.1 degree for
// ~150 matches of 0.1-0.2 px noise at ~1 m), with a symmetric positive definite covariance.
TEST(Tracker, TracksFromASavedMapAgainstExactGroundTruth) {
  const SavedMap saved("api_tracker_map");
  Tracker tracker = Tracker::openMap(saved.folder);
  EXPECT_EQ(tracker.mode(), Tracker::Mode::SixDof);
  EXPECT_EQ(tracker.imageSize(), saved.world.size);
  ASSERT_TRUE(tracker.camera().has_value());
  EXPECT_TRUE(tracker.camera()->isApprox(saved.world.K));
  double maxT = 0.0, maxR = 0.0, sumSquaredZ = 0.0;
  std::set<int> referencesUsed;
  for (int k = 0; k < 40; ++k) {
    const RigidPose truth =
        saved.world.worldToCamera(PlaneMultiWorld::cameraAlong(-0.28 + 0.014 * k, k));
    const Tracker::Result r = tracker.track(
        saved.world.render(PlaneMultiWorld::cameraAlong(-0.28 + 0.014 * k, k), 100 + k));
    ASSERT_EQ(r.state, Tracker::State::Tracking) << k << ": " << r.reason;
    EXPECT_EQ(r.frameIndex, k);
    ASSERT_TRUE(r.worldToCamera && r.covariance) << k;
    EXPECT_FALSE(r.homography.has_value());
    EXPECT_GE(r.inliers, 15) << k;  // PoseTrackerLimits::minInliers
    EXPECT_GT(r.milliseconds, 0.0);
    referencesUsed.insert(r.referenceA);
    referencesUsed.insert(r.referenceB);
    // Error over predicted SD, per component of (t, r).
    const Vector6d dx = r.worldToCamera->toVector6() - truth.toVector6();
    sumSquaredZ += dx.cwiseQuotient(r.covariance->diagonal().cwiseSqrt()).squaredNorm();
    maxT = std::max(maxT, translationErrorMm(*r.worldToCamera, truth));
    maxR = std::max(maxR, rotationErrorDeg(*r.worldToCamera, truth));
    const Eigen::Matrix<double, 6, 6>& C = *r.covariance;
    EXPECT_LT((C - C.transpose()).norm(), 1e-12 * C.norm()) << k;
    EXPECT_EQ(Eigen::LLT<Matrix6d>(C).info(), Eigen::Success) << k;
  }
  EXPECT_GE(referencesUsed.size(), 3u);  // x from -0.28 to 0.27: at least two pairs
  EXPECT_LT(maxT, 2.0);
  EXPECT_LT(maxR, 0.1);
  // The covariance predicts the spread of the error to within a small factor: the RMS of error /
  // predicted SD over the 6 components of the 40 frames measured 2.3 (Omega_k counts the frame's
  // corner noise, not the map's: the map points come from noisy reference corners).
  const double rmsZ = std::sqrt(sumSquaredZ / (6.0 * 40.0));
  EXPECT_GT(rmsZ, 0.5);
  EXPECT_LT(rmsZ, 5.0);
  RecordProperty("rms_error_over_predicted_sd", std::to_string(rmsZ));
  RecordProperty("max_translation_error_mm", std::to_string(maxT));
  RecordProperty("max_rotation_error_deg", std::to_string(maxR));
}

// The covariance is the tracker's Omega_k of x_Ak (pose relative to reference A) carried to the
// world -> camera 6-vector: compared with J Omega_k J^T, J by central differences of
// x_Ak -> vec6(T(x_Ak) T_A) — an independent route to the same first-order propagation.
TEST(Tracker, CovarianceIsTheTrackersOmegaCarriedToTheWorldFrame) {
  const SavedMap saved("api_tracker_covariance");
  const int frames = 6;
  std::vector<MultiReferenceResult> expected;
  {
    MultiReferenceTracker direct(MultiReferenceMap::load(saved.folder), TrackerParams{});
    for (int k = 0; k < frames; ++k)
      expected.push_back(direct.process(
          saved.world.render(PlaneMultiWorld::cameraAlong(-0.2 + 0.01 * k, k), 300 + k)));
  }
  Tracker tracker = Tracker::openMap(saved.folder);
  for (int k = 0; k < frames; ++k) {
    const Tracker::Result r = tracker.track(
        saved.world.render(PlaneMultiWorld::cameraAlong(-0.2 + 0.01 * k, k), 300 + k));
    const PoseTrackingResult& e = expected[static_cast<std::size_t>(k)].tracking;
    ASSERT_EQ(r.state, Tracker::State::Tracking) << k << ": " << r.reason;
    ASSERT_TRUE(e.worldToCamera && e.T_Ak && r.worldToCamera && r.covariance) << k;
    // The same tracker on the same frames: the same pose (deterministic to rounding).
    EXPECT_LT(translationErrorMm(*r.worldToCamera, *e.worldToCamera), 1e-6) << k;
    const RigidPose T_A = e.T_Ak->inverse() * *e.worldToCamera;
    const Vector6d x = e.T_Ak->toVector6();
    Matrix6d J;
    const double h = 1e-6;
    for (int i = 0; i < 6; ++i) {
      Vector6d plus = x, minus = x;
      plus[i] += h;
      minus[i] -= h;
      J.col(i) = ((RigidPose::fromVector6(plus) * T_A).toVector6() -
                  (RigidPose::fromVector6(minus) * T_A).toVector6()) /
                 (2.0 * h);
    }
    const Matrix6d want = J * e.covariance * J.transpose();
    // Central differences of a smooth map at h = 1e-6: ~1e-9 relative error in J.
    EXPECT_LT((*r.covariance - want).norm(), 1e-6 * want.norm()) << k << "\n" << *r.covariance;
  }
}

// A first frame far from the first pair, rolled 35 degrees: the relocaliser places it (exact pose
// within 2 mm / 0.1 degree, as above); a black frame is lost with a reason and no pose; reset()
// starts counting frames again.
TEST(Tracker, RelocalisesReportsLostFramesAndResets) {
  const SavedMap saved("api_tracker_lost");
  Tracker tracker = Tracker::openMap(saved.folder);
  const RigidPose roll(Eigen::AngleAxisd(35.0 * CV_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix(),
                       Eigen::Vector3d::Zero());
  const RigidPose fromA = roll * PlaneMultiWorld::cameraAt(0.27, 0.02, -0.15);
  const RigidPose truth = saved.world.worldToCamera(fromA);
  const Tracker::Result first = tracker.track(saved.world.render(fromA, 500));
  ASSERT_EQ(first.state, Tracker::State::Tracking) << first.reason;
  EXPECT_TRUE(first.relocalised);
  EXPECT_EQ(first.reason, "relocalised");
  EXPECT_LT(translationErrorMm(*first.worldToCamera, truth), 2.0);
  EXPECT_LT(rotationErrorDeg(*first.worldToCamera, truth), 0.1);

  const Tracker::Result black =
      tracker.track(cv::Mat(saved.world.size, CV_8UC3, cv::Scalar::all(0)));
  EXPECT_EQ(black.state, Tracker::State::Lost);
  EXPECT_STREQ(toString(black.state), "lost");
  EXPECT_FALSE(black.reason.empty());
  EXPECT_FALSE(black.worldToCamera.has_value());
  EXPECT_FALSE(black.covariance.has_value());
  EXPECT_EQ(black.frameIndex, 1);

  tracker.reset();
  const Tracker::Result again =
      tracker.track(cv::Mat(saved.world.size, CV_8UC3, cv::Scalar::all(0)));
  EXPECT_EQ(again.frameIndex, 0);
  EXPECT_NE(again.state, Tracker::State::Tracking);
  EXPECT_THROW(tracker.track(cv::Mat(240, 320, CV_8UC3, cv::Scalar::all(0))), Error);
  EXPECT_THROW(tracker.track(cv::Mat()), Error);
}

// pose.max_predicted_error_px: with a limit below every frame's predicted overlay error each
// tracked frame is Uncertain (pose, covariance and prediction given, the reason names the limit)
// and the tracker goes on from it — the same poses frame by frame as with a limit never reached,
// which leaves the frames Tracking. The prediction follows the overlay points it is given, and on
// exact ground truth it is of the size of the true error or above it (see below).
TEST(Tracker, AFrameAboveThePredictedErrorLimitIsUncertainAndTrackingGoesOn) {
  const SavedMap saved("api_tracker_uncertain");
  TrackerParams low, high;
  low.pose.maxPredictedErrorPx = 1e-4;
  high.pose.maxPredictedErrorPx = 1e6;
  Tracker uncertain = Tracker::openMap(saved.folder, low);
  Tracker tracking = Tracker::openMap(saved.folder, high);
  // A 5 cm cube on the plane in front of reference A (the world is the plane's frame: A's frame
  // carried by T_A).
  const RigidPose T_A = saved.world.T_A;
  std::vector<Eigen::Vector3d> cube;
  for (int i = 0; i < 8; ++i)
    cube.push_back(T_A.inverse() * Eigen::Vector3d(i & 1 ? 0.025 : -0.025, i & 2 ? 0.025 : -0.025,
                                                   i & 4 ? 0.95 : 1.0));
  uncertain.setOverlayPoints(cube);
  tracking.setOverlayPoints(cube);
  // Another object (4 times the size, farther out) on a third tracker over the same frames.
  std::vector<Eigen::Vector3d> larger;
  for (const Eigen::Vector3d& X : cube)
    larger.push_back(T_A.inverse() * (Eigen::Vector3d(0.05, 0.0, 0.9) + 4.0 * (T_A * X)));
  Tracker other = Tracker::openMap(saved.folder, high);
  other.setOverlayPoints(larger);
  const PinholeCamera camera(saved.world.K, saved.world.size);
  std::vector<double> ratios;
  for (int k = 0; k < 12; ++k) {
    const RigidPose fromA = PlaneMultiWorld::cameraAlong(-0.2 + 0.012 * k, k);
    const cv::Mat frame = saved.world.render(fromA, 700 + k);
    const Tracker::Result u = uncertain.track(frame);
    const Tracker::Result t = tracking.track(frame);
    ASSERT_EQ(t.state, Tracker::State::Tracking) << k << ": " << t.reason;
    ASSERT_EQ(u.state, Tracker::State::Uncertain) << k << ": " << u.reason;
    EXPECT_STREQ(toString(u.state), "uncertain");
    EXPECT_NE(u.reason.find("> pose.max_predicted_error_px 0.0001"), std::string::npos) << u.reason;
    ASSERT_TRUE(u.worldToCamera && u.covariance && u.predictedErrorPx && t.predictedErrorPx) << k;
    EXPECT_LT(translationErrorMm(*u.worldToCamera, *t.worldToCamera), 1e-9) << k;
    EXPECT_DOUBLE_EQ(*u.predictedErrorPx, *t.predictedErrorPx) << k;
    EXPECT_GT(*t.predictedErrorPx, 1e-4) << k;
    // The objects' predictions are in the ratio of the world covariance's for their points (the
    // same figures to first order as from Omega_k in camera A's frame; the frame's a-posteriori
    // factor and the calibration are common to both).
    const Tracker::Result o = other.track(frame);
    ASSERT_TRUE(o.predictedErrorPx) << k;
    const double want = *predictedOverlayErrorPx(camera, *t.worldToCamera, *t.covariance, larger) /
                        *predictedOverlayErrorPx(camera, *t.worldToCamera, *t.covariance, cube);
    EXPECT_NEAR(*o.predictedErrorPx / *t.predictedErrorPx, want, 1e-6 * want) << k;
    EXPECT_GT(std::abs(want - 1.0), 0.1) << k;  // the objects differ
    const std::optional<double> trueError =
        overlayErrorPx(camera, saved.world.worldToCamera(fromA), *t.worldToCamera, cube);
    ratios.push_back(*trueError / *t.predictedErrorPx);
  }
  std::sort(ratios.begin(), ratios.end());
  const double median = ratios[ratios.size() / 2];
  // Measured 0.34: on this exact map the errors are the frames' corner noise, which the temporal
  // prior averages out while the prediction (rescaled by the matches alone and calibrated on real
  // clips, whose errors are shared by all frames) does not credit it — conservative. Three times
  // lower, or above the band (1.6), the prediction would be broken.
  EXPECT_GT(median, 0.1);
  EXPECT_LT(median, 1.6);
  RecordProperty("median_true_over_predicted", std::to_string(median));
  // Homography mode has no pose covariance to predict from.
  const std::filesystem::path dir = test::freshTempDir("api_tracker_uncertain_homography");
  ASSERT_TRUE(cv::imwrite((dir / "reference.png").string(), test::texturedImage({320, 240}, 32)));
  Tracker homography = Tracker::openReference(dir / "reference.png");
  EXPECT_THROW(homography.setOverlayPoints(cube), Error);
}

// Rotation-only camera (any scene): frame k = the reference through H_k = K R_k K^-1.
Eigen::Matrix3d panTilt(int k) {
  return (Eigen::AngleAxisd(0.004 * k, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(-0.002 * k, Eigen::Vector3d::UnitX()))
      .matrix();
}
cv::Matx33d homographyOf(const Eigen::Matrix3d& K, const Eigen::Matrix3d& R) {
  const Eigen::Matrix3d H = K * R * K.inverse();
  cv::Matx33d out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = H(r, c);
  return out;
}

// Homography mode from files (reference image + camera.yml): an unrelated first frame is still
// initialising, the panning frames are registered (HomographyTracker_test's bound: image-corner
// error < 0.8 px at noise SD 2) with the rotation pose, and an unrelated frame after them is lost.
TEST(Tracker, HomographyModeFromAReferenceImageAndCamera) {
  const std::filesystem::path dir = test::freshTempDir("api_tracker_homography");
  const cv::Size size(320, 240);
  Eigen::Matrix3d K;
  K << 300, 0, 159.5, 0, 300, 119.5, 0, 0, 1;
  const cv::Mat reference = test::texturedImage(size, 31);
  ASSERT_TRUE(cv::imwrite((dir / "reference.png").string(), reference));
  PinholeCamera(K, size).save(dir / "camera.yml");
  Tracker tracker = Tracker::openReference(dir / "reference.png", dir / "camera.yml");
  EXPECT_EQ(tracker.mode(), Tracker::Mode::Homography);
  EXPECT_EQ(tracker.imageSize(), size);

  const Tracker::Result unrelated = tracker.track(test::texturedImage(size, 99));
  EXPECT_EQ(unrelated.state, Tracker::State::Initialising);
  EXPECT_FALSE(unrelated.reason.empty());
  EXPECT_FALSE(unrelated.homography.has_value());

  double worstPx = 0.0, worstDeg = 0.0;
  for (int k = 1; k <= 12; ++k) {
    const cv::Matx33d truth = homographyOf(K, panTilt(k));
    const Tracker::Result r =
        tracker.track(test::withNoise(test::warpedBy(reference, truth), 2.0, k));
    ASSERT_EQ(r.state, Tracker::State::Tracking) << k << ": " << r.reason;
    ASSERT_TRUE(r.homography && r.worldToCamera) << k;
    EXPECT_FALSE(r.covariance.has_value());
    EXPECT_EQ(r.worldToCamera->translation().norm(), 0.0);
    worstPx = std::max(worstPx, test::cornerError(*r.homography, truth, size));
    worstDeg = std::max(worstDeg, rotationErrorDeg(*r.worldToCamera, RigidPose(panTilt(k), {})));
  }
  EXPECT_LT(worstPx, 0.8);
  // 0.8 px at the image corners, ~200 px from the centre at f = 300: at most ~0.15 degree.
  EXPECT_LT(worstDeg, 0.15);
  RecordProperty("max_corner_error_px", std::to_string(worstPx));
  RecordProperty("max_rotation_error_deg", std::to_string(worstDeg));

  const Tracker::Result lost = tracker.track(test::texturedImage(size, 98));
  EXPECT_EQ(lost.state, Tracker::State::Lost);
  EXPECT_FALSE(lost.reason.empty());
  // Parameters given as a struct (what the Python module passes) instead of a file.
  TrackerParams params;
  params.ransac.maxIterations = 90;
  Tracker withParams = Tracker::openReference(dir / "reference.png", dir / "camera.yml", params);
  EXPECT_EQ(withParams.track(test::warpedBy(reference, homographyOf(K, panTilt(1)))).state,
            Tracker::State::Tracking);
}

// A reference photographed by another camera (320x240) tracked in frames of 480x360: accepted
// without a camera file (imageSize() empty: any size), registered to the same accuracy; given
// the frames' camera, the frames must have its size and no rotation pose is reported (the
// reference's intrinsics are unknown).
TEST(Tracker, HomographyModeWithFramesOfAnotherSizeThanTheReference) {
  const std::filesystem::path dir = test::freshTempDir("api_tracker_sizes");
  const cv::Size refSize(320, 240), frameSize(480, 360);
  const cv::Mat reference = test::texturedImage(refSize, 33);
  ASSERT_TRUE(cv::imwrite((dir / "reference.png").string(), reference));
  PinholeCamera::fromFieldOfView(frameSize, 60.0).save(dir / "camera.yml");
  for (const bool camera : {false, true}) {
    Tracker tracker = camera ? Tracker::openReference(dir / "reference.png", dir / "camera.yml")
                             : Tracker::openReference(dir / "reference.png");
    EXPECT_EQ(tracker.imageSize(), camera ? frameSize : cv::Size());
    EXPECT_EQ(tracker.referenceSize(), refSize);
    for (int k = 0; k < 5; ++k) {
      const cv::Matx33d truth = cv::Matx33d(1.5, 0, 0, 0, 1.5, 0, 0, 0, 1) *
                                test::tiltedView(refSize, 8.0 + k, 0.95, 5.0 * k);
      const Tracker::Result r =
          tracker.track(test::withNoise(test::warpedBy(reference, truth, frameSize), 2.0, 60 + k));
      ASSERT_EQ(r.state, Tracker::State::Tracking) << k << ": " << r.reason;
      ASSERT_TRUE(r.homography.has_value());
      EXPECT_FALSE(r.worldToCamera.has_value());
      EXPECT_LT(test::cornerError(*r.homography, truth, frameSize), 0.5) << k;
    }
  }
}

TEST(Tracker, BadInputsAreClearErrors) {
  const std::filesystem::path dir = test::freshTempDir("api_tracker_errors");
  const auto message = [](const auto& open) {
    try {
      open();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([&] { Tracker::openMap(dir / "missing"); }).find("missing"), std::string::npos);
  EXPECT_NE(message([&] { Tracker::openReference(dir / "nothing.png"); }).find("nothing.png"),
            std::string::npos);
  const cv::Mat reference = test::texturedImage({320, 240}, 32);
  ASSERT_TRUE(cv::imwrite((dir / "reference.png").string(), reference));
  // The camera is the frames': a frame of another size than its is an error naming both.
  PinholeCamera::fromFieldOfView({640, 480}, 60.0).save(dir / "camera.yml");
  Tracker withCamera = Tracker::openReference(dir / "reference.png", dir / "camera.yml");
  EXPECT_EQ(withCamera.imageSize(), cv::Size(640, 480));
  EXPECT_EQ(withCamera.referenceSize(), cv::Size(320, 240));
  const std::string wrongSize = message([&] { withCamera.track(reference); });
  EXPECT_NE(wrongSize.find("320x240"), std::string::npos) << wrongSize;
  EXPECT_NE(wrongSize.find("camera is 640x480"), std::string::npos) << wrongSize;
  TrackerOptions options;
  options.params = dir / "absent.yml";
  EXPECT_NE(message([&] {
              Tracker::openReference(dir / "reference.png", {}, options);
            }).find("absent.yml"),
            std::string::npos);
  TrackerParams bad;
  bad.ransac.maxIterations = 0;
  EXPECT_NE(message([&] {
              Tracker::openReference(dir / "reference.png", {}, bad);
            }).find("ransac.max_iterations"),
            std::string::npos);
}

}  // namespace
}  // namespace reftrack
