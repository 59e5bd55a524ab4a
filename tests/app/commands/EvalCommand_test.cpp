#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <random>

#include "DatasetFixtures.hpp"
#include "app/commands/CommandTestSupport.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/TumTrajectory.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

using namespace reftrack;

namespace {

// Ground truth: a camera sliding along x above the marker, looking straight down; 100 frames.
TumTrajectory slide() {
  TumTrajectory t;
  const Eigen::Matrix3d down = Eigen::Vector3d(1, -1, -1).asDiagonal();  // z_cam = -z_world
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3d C(-0.1 + 0.002 * k, 0.02, 0.5);
    t.poses.push_back({k / 30.0, RigidPose(down, -down * C)});
  }
  return t;
}

}  // namespace

TEST(EvalCommand, KnownOffsetGivesKnownAteInJsonAndWritesPlots) {
  const auto dir = test::freshTempDir("EvalCommand_Offset");
  const TumTrajectory gt = slide();
  TumTrajectory est;
  for (std::size_t k = 0; k < gt.poses.size(); ++k) {
    if (k >= 80) break;  // the tracker lost the last 20 frames
    est.poses.push_back({gt.poses[k].timestamp,
                         gt.poses[k].worldToCamera *
                             RigidPose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -0.01))});
  }
  gt.save(dir / "gt.txt");
  est.save(dir / "est.txt");
  Eigen::Matrix3d K;
  K << 500, 0, 319.5, 0, 500, 239.5, 0, 0, 1;
  PinholeCamera(K, {640, 480}).save(dir / "camera.yml");

  const auto r = test::runReftrack("eval --gt " + (dir / "gt.txt").string() + " --est " +
                                       (dir / "est.txt").string() + " --camera " +
                                       (dir / "camera.yml").string() + " --json",
                                   dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // One JSON object on stdout.
  ASSERT_FALSE(r.out.empty());
  EXPECT_EQ(r.out.front(), '{');
  EXPECT_EQ(r.out[r.out.find_last_not_of('\n')], '}');
  // Camera centres moved 10 mm along world z for every frame: ATE exactly 10 mm.
  EXPECT_NE(r.out.find("\"ate_translation_mm\": {\"count\": 80, \"rmse\": 10, \"mean\": 10"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\"tracked_fraction\": 0.8"), std::string::npos) << r.out;
  // A 10 mm depth change at 0.5 m: cube vertices move by about 2% of their offset from the
  // principal point, a couple of pixels; the exact value is checked in TrajectoryEvaluator_test.
  EXPECT_NE(r.out.find("\"cube_error_px\": {\"count\": 640"), std::string::npos) << r.out;
  const cv::Mat errorPlot = cv::imread((dir / "est.error.png").string());
  const cv::Mat topPlot = cv::imread((dir / "est.topview.png").string());
  EXPECT_EQ(errorPlot.size(), cv::Size(900, 600));
  EXPECT_EQ(topPlot.size(), cv::Size(900, 600));

  const auto text = test::runReftrack(
      "eval --no-plots --gt " + (dir / "gt.txt").string() + " --est " + (dir / "est.txt").string(),
      dir);
  ASSERT_EQ(text.exitCode, 0) << text.err;
  EXPECT_NE(text.out.find("tracked 80.0%"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("needs --camera"), std::string::npos) << text.out;
}

TEST(EvalCommand, ErrorsAreClear) {
  const auto dir = test::freshTempDir("EvalCommand_Errors");
  EXPECT_EQ(test::runReftrack("eval --gt nothing.txt --est nothing.txt", dir).exitCode, 2);
  slide().save(dir / "gt.txt");
  std::ofstream(dir / "bad.txt") << "0 1 2\n";
  const auto r = test::runReftrack(
      "eval --gt " + (dir / "gt.txt").string() + " --est " + (dir / "bad.txt").string(), dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("line 1"), std::string::npos) << r.err;
}

namespace {

// The first number after `key` in a JSON text (e.g. "\"rmse\": ").
double numberAfter(const std::string& json, const std::string& key, std::size_t from = 0) {
  const std::size_t at = json.find(key, from);
  if (at == std::string::npos) return std::nan("");
  return std::stod(json.substr(at + key.size()));
}

}  // namespace

// --anchor-map: an estimate in a map's own world (a rigid transform G away from the truth's),
// carried into the truth's by the map's reference 0 and the truth's pose at its time: exact
// poses give no error at all; a reference 0 posed 2 mm off shows up as a cube error; the cube
// placed with --cube-at or --cube-ahead.
TEST(EvalCommand, AnchorMapCarriesTheEstimateIntoTheTruthsWorld) {
  const auto dir = test::freshTempDir("EvalCommand_Anchor");
  const TumTrajectory gt = slide();
  gt.save(dir / "gt.txt");
  Eigen::Matrix3d K;
  K << 500, 0, 319.5, 0, 500, 239.5, 0, 0, 1;
  const PinholeCamera camera(K, {640, 480});
  camera.save(dir / "camera.yml");
  // The map's world: the truth's turned 30 degrees and shifted (X_map = G X_truth).
  const RigidPose G(
      Eigen::AngleAxisd(0.52, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix(),
      Eigen::Vector3d(0.3, -0.2, 0.1));
  TumTrajectory est;
  for (const StampedPose& p : gt.poses)
    est.poses.push_back({p.timestamp, p.worldToCamera * G.inverse()});
  est.save(dir / "est.txt");
  const auto saveMap = [&](const RigidPose& reference0, const std::filesystem::path& folder) {
    MultiReferenceMap map;
    map.camera = camera;
    map.poseSource = "test";
    for (int v = 0; v < 2; ++v) {
      ReferenceView view;
      view.name = "reference_0" + std::to_string(v) + ".png";
      view.T = v == 0 ? reference0 : gt.poses[40].worldToCamera * G.inverse();
      view.image = cv::Mat(480, 640, CV_8UC1, cv::Scalar(100));
      map.views.push_back(view);
    }
    map.save(folder);
  };
  saveMap(gt.poses[10].worldToCamera * G.inverse(), dir / "map");
  const std::string common = "eval --gt " + (dir / "gt.txt").string() + " --est " +
                             (dir / "est.txt").string() + " --camera " +
                             (dir / "camera.yml").string() + " --json --no-plots";
  const auto anchored =
      test::runReftrack(common + " --anchor-map " + (dir / "map").string() + " --anchor-time " +
                            std::to_string(10 / 30.0) + " --cube-at 0.01,0.02,0",
                        dir);
  ASSERT_EQ(anchored.exitCode, 0) << anchored.err;
  EXPECT_LT(numberAfter(anchored.out, "\"cube_error_px\": {\"count\": 800, \"rmse\": "), 1e-6)
      << anchored.out;
  EXPECT_LT(numberAfter(anchored.out, "\"ate_translation_mm\": {\"count\": 100, \"rmse\": "), 1e-6)
      << anchored.out;
  // Without the anchor, the worlds differ: metres off.
  const auto plain = test::runReftrack(common, dir);
  EXPECT_GT(numberAfter(plain.out, "\"ate_translation_mm\": {\"count\": 100, \"rmse\": "), 100.0);
  // Reference 0 posed 2 mm off along the camera's x: every frame's cube a few pixels off
  // (2 mm at 0.5 m through 500 px: 2 px).
  saveMap(RigidPose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.002, 0, 0)) *
              gt.poses[10].worldToCamera * G.inverse(),
          dir / "off");
  const auto off =
      test::runReftrack(common + " --anchor-map " + (dir / "off").string() + " --anchor-time " +
                            std::to_string(10 / 30.0) + " --cube-ahead 0.5",
                        dir);
  ASSERT_EQ(off.exitCode, 0) << off.err;
  const double cube = numberAfter(off.out, "\"cube_error_px\": {\"count\": 800, \"rmse\": ");
  EXPECT_GT(cube, 1.5) << off.out;
  EXPECT_LT(cube, 2.5) << off.out;
  // Usage: --anchor-time alone, --cube-ahead without the map, the anchor with a fitted
  // alignment; and a time the truth does not cover.
  EXPECT_EQ(test::runReftrack(common + " --anchor-time 0", dir).exitCode, 2);
  EXPECT_EQ(test::runReftrack(common + " --cube-ahead 1", dir).exitCode, 2);
  EXPECT_EQ(
      test::runReftrack(
          common + " --anchor-map " + (dir / "map").string() + " --anchor-time 0 --align se3", dir)
          .exitCode,
      2);
  const auto beyond = test::runReftrack(
      common + " --anchor-map " + (dir / "map").string() + " --anchor-time 50", dir);
  EXPECT_EQ(beyond.exitCode, 1);
  EXPECT_NE(beyond.err.find("--anchor-time 50: the ground truth has no pose there"),
            std::string::npos)
      << beyond.err;
}

// EuRoC ground truth (body poses at 200 Hz through T_BS, camera frames at 20 Hz) against an
// estimate in another world frame: a known Sim(3) plus known noise on the camera centres.
// --align sim3 leaves exactly the noise; the default (none, stated) keeps the frame offset.
TEST(EvalCommand, EurocGroundTruthWithSim3AlignmentLeavesTheKnownNoise) {
  const auto dir = test::freshTempDir("EvalCommand_Euroc");
  const long long t0 = 1403636579763555584LL;
  const auto cameraPose = [](double t) {  // slide(): 0.06 m/s along x, looking down
    const Eigen::Matrix3d down = Eigen::Vector3d(1, -1, -1).asDiagonal();
    const Eigen::Vector3d C(-0.1 + 0.06 * t, 0.02 + 0.1 * std::sin(0.5 * t),
                            0.5 + 0.05 * std::cos(0.7 * t));
    return RigidPose(down, -down * C);
  };
  std::vector<std::pair<long long, RigidPose>> mocap;
  for (int k = 0; k < 3000; ++k) mocap.push_back({t0 + k * 5000000LL, cameraPose(k * 0.005)});
  std::vector<long long> frameNs;
  for (int k = 0; k < 300; ++k) frameNs.push_back(t0 + 2500000LL + k * 50000000LL);
  const RigidPose tbs(Eigen::Quaterniond(0.71, 0.0, 0.0, 0.70).normalized(),
                      Eigen::Vector3d(-0.02, -0.06, 0.01));
  test::writeEurocSequence(dir, std::vector<cv::Mat>(300, cv::Mat(24, 32, CV_8UC1)), frameNs,
                           PinholeCamera::fromFieldOfView({32, 24}, 60.0), tbs, mocap);

  // The estimate: frames 0..279 (tracked), in a world X_est = (R^T (X_gt - t)) / s, centres with
  // 3 mm noise per coordinate in the ground-truth frame.
  const double s = 0.8;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.9, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d t(1.0, -2.0, 0.3);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.003);
  TumTrajectory est;
  double noiseSq = 0;
  for (int k = 0; k < 280; ++k) {
    const double time = frameNs[static_cast<std::size_t>(k)] * 1e-9;
    // The camera pose at the frame time (linear interpolation between the 5 ms samples misses
    // the curvature of the sine terms by at most 0.1 * 0.25 * 0.005^2 / 8 = 8e-8 m).
    const RigidPose truth = cameraPose((frameNs[static_cast<std::size_t>(k)] - t0) * 1e-9);
    const Eigen::Vector3d n(noise(rng), noise(rng), noise(rng));
    noiseSq += n.squaredNorm();
    const Eigen::Vector3d c = R.transpose() * (truth.cameraCentre() + n - t) / s;
    const Eigen::Matrix3d Rwc = truth.rotation() * R;
    est.poses.push_back({time, RigidPose(Rwc, -Rwc * c)});
  }
  est.save(dir / "est.txt");
  const double noiseRmsMm = 1000.0 * std::sqrt(noiseSq / 280);

  const std::string gt = "euroc:" + dir.string();
  const auto sim3 = test::runReftrack(
      "eval --no-plots --json --align sim3 --gt " + gt + " --est " + (dir / "est.txt").string(),
      dir);
  ASSERT_EQ(sim3.exitCode, 0) << sim3.err;
  EXPECT_NE(sim3.out.find("\"alignment\": \"sim3\""), std::string::npos) << sim3.out;
  // 300 camera frames, each with an interpolated ground-truth pose; 280 estimated and associated.
  EXPECT_NE(sim3.out.find("\"ground_truth_frames\": 300"), std::string::npos) << sim3.out;
  EXPECT_NE(sim3.out.find("\"associated_frames\": 280"), std::string::npos) << sim3.out;
  EXPECT_NE(sim3.out.find("\"tracked_fraction\": 0.933333"), std::string::npos) << sim3.out;
  // Umeyama recovers the scale to ~0.2% from 280 centres 3 mm noisy over a 0.9 m path.
  EXPECT_NEAR(numberAfter(sim3.out, "\"alignment_scale\": "), s, 0.01 * s) << sim3.out;
  // The fit absorbs 7 of the 840 noise degrees of freedom: residual RMS = noise RMS times
  // sqrt(1 - 7/840) = 0.996 on average (spread ~0.2%); 2% is a generous bound.
  const double rmse = numberAfter(sim3.out, "\"rmse\": ", sim3.out.find("ate_translation_mm"));
  EXPECT_NEAR(rmse, noiseRmsMm, 0.02 * noiseRmsMm) << sim3.out;
  EXPECT_LE(rmse, noiseRmsMm * 1.0001) << sim3.out;

  // Default: no alignment, stated; the other world frame is metres away.
  const auto none =
      test::runReftrack("eval --no-plots --gt " + gt + " --est " + (dir / "est.txt").string(), dir);
  ASSERT_EQ(none.exitCode, 0) << none.err;
  EXPECT_NE(none.out.find("alignment: none (the default"), std::string::npos) << none.out;
  EXPECT_NE(none.out.find("EuRoC ground truth"), std::string::npos) << none.out;
  EXPECT_NE(none.out.find("3000 samples interpolated at 300 of the 300 frame times"),
            std::string::npos)
      << none.out;
}

// TUM RGB-D ground truth at the rgb.txt frame times; an estimate 50 mm off in the world gives
// exactly 50 mm without alignment and 0 with se3.
TEST(EvalCommand, TumGroundTruthWithoutAlignmentGivesTheKnownOffset) {
  const auto dir = test::freshTempDir("EvalCommand_Tum");
  const TumTrajectory gt = slide();
  TumTrajectory mocap, est;
  std::vector<double> times;
  const double t0 = 1305031102.175304;
  for (const StampedPose& p : gt.poses) {
    times.push_back(t0 + p.timestamp);
    mocap.poses.push_back({t0 + p.timestamp, p.worldToCamera});
    const Eigen::Vector3d c = p.worldToCamera.cameraCentre() + Eigen::Vector3d(0, 0.03, 0.04);
    est.poses.push_back(
        {t0 + p.timestamp, RigidPose(p.worldToCamera.rotation(), -p.worldToCamera.rotation() * c)});
  }
  test::writeTumSequence(dir, std::vector<cv::Mat>(times.size(), cv::Mat(8, 8, CV_8UC3)), times,
                         mocap);
  est.save(dir / "est.txt");
  const std::string args =
      " --no-plots --json --gt tum:" + dir.string() + " --est " + (dir / "est.txt").string();
  const auto none = test::runReftrack("eval" + args, dir);
  ASSERT_EQ(none.exitCode, 0) << none.err;
  EXPECT_NE(none.out.find("\"alignment\": \"none\""), std::string::npos) << none.out;
  // Timestamps round-trip through 6 decimals on both sides: the offset is 50 mm to 1e-6 mm.
  const std::size_t ate = none.out.find("ate_translation_mm");
  EXPECT_NEAR(numberAfter(none.out, "\"rmse\": ", ate), 50.0, 1e-4) << none.out;
  EXPECT_NEAR(numberAfter(none.out, "\"max\": ", ate), 50.0, 1e-4) << none.out;
  const auto se3 = test::runReftrack("eval --align se3" + args, dir);
  ASSERT_EQ(se3.exitCode, 0) << se3.err;
  EXPECT_NEAR(numberAfter(se3.out, "\"max\": ", se3.out.find("ate_translation_mm")), 0.0, 1e-3)
      << se3.out;
}

TEST(EvalCommand, BadDatasetGroundTruthIsAClearError) {
  const auto dir = test::freshTempDir("EvalCommand_BadDataset");
  slide().save(dir / "est.txt");
  const auto r = test::runReftrack(
      "eval --no-plots --gt euroc:" + dir.string() + " --est " + (dir / "est.txt").string(), dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("expected DIR/mav0/cam0"), std::string::npos) << r.err;
  const auto align = test::runReftrack("eval --align affine --gt " + (dir / "est.txt").string() +
                                           " --est " + (dir / "est.txt").string(),
                                       dir);
  EXPECT_EQ(align.exitCode, 2);
}
