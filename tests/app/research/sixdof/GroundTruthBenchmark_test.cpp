#include "app/research/sixdof/GroundTruthBenchmark.hpp"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <set>

#include "ErrorMessage.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {
namespace {

PinholeCamera smallCamera() {
  Eigen::Matrix3d K;
  K << 420, 0, 355.2, 0, 421, 250.3, 0, 0, 1;
  return PinholeCamera(K, cv::Size(752, 480), {-0.3, 0.08, 0, 0, 0});
}

// A camera 0.35 m above the board looking down at (0.16, -0.10, 0), as on the desk clip.
RigidPose lookingDown(const Eigen::Vector3d& offset, double rollRad) {
  const Eigen::Matrix3d down = Eigen::Vector3d(1, -1, -1).asDiagonal();
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(rollRad, Eigen::Vector3d::UnitZ()).toRotationMatrix() * down;
  return RigidPose(R, -R * (Eigen::Vector3d(0.16, -0.10, 0.35) + offset));
}

// The score is what OpenCV's own projection gives: the mean distance of the 8 vertices through
// cv::projectPoints with K and no distortion (the lens plays no part in the score).
TEST(GroundTruthBenchmark, CubeErrorIsTheMeanVertexDistanceThroughKAlone) {
  const PinholeCamera camera = smallCamera();
  const std::vector<Eigen::Vector3d> cube = cubeOn({0.16, -0.10, 0.0}, 0.1);
  ASSERT_EQ(cube.size(), 8u);
  for (const Eigen::Vector3d& v : cube) {
    EXPECT_NEAR(std::abs(v.x() - 0.16), 0.05, 1e-12);
    EXPECT_NEAR(std::abs(v.y() + 0.10), 0.05, 1e-12);
    EXPECT_TRUE(v.z() == 0.0 || v.z() == 0.1);  // standing on z = 0, up to +z
  }
  const RigidPose truth = lookingDown({0.01, -0.02, 0.0}, 0.1);
  EXPECT_DOUBLE_EQ(cubeErrorPx(camera, cube, truth, truth), 0.0);
  const RigidPose estimate = lookingDown({0.013, -0.018, 0.004}, 0.103);
  auto project = [&](const RigidPose& T) {
    std::vector<cv::Point3d> X;
    for (const Eigen::Vector3d& v : cube) X.emplace_back(v.x(), v.y(), v.z());
    const Eigen::Vector3d r = axisAngleFromRotation(T.rotation());
    const cv::Vec3d rvec(r.x(), r.y(), r.z()),
        tvec(T.translation().x(), T.translation().y(), T.translation().z());
    std::vector<cv::Point2d> p;
    cv::projectPoints(X, rvec, tvec, cv::Mat(camera.Kcv()), cv::noArray(), p);
    return p;
  };
  const std::vector<cv::Point2d> a = project(truth), b = project(estimate);
  double mean = 0;
  for (std::size_t i = 0; i < 8; ++i) mean += cv::norm(a[i] - b[i]) / 8.0;
  EXPECT_GT(mean, 1.0);
  EXPECT_NEAR(cubeErrorPx(camera, cube, truth, estimate), mean, 1e-9);
  // A pose that puts the whole cube behind the camera is infinitely wrong.
  const RigidPose behind(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -5));
  EXPECT_TRUE(std::isinf(cubeErrorPx(camera, cube, truth, behind)));
}

// Coverage, mean / p95 / max and the wrong (> 5 px) and good (<= 1.5 px) counts are over the
// frames with a true pose; a pose on a frame without one is not scored. A pose that put the cube
// behind the camera (infinite error) is posed and wrong, but left out of mean / p95 / max.
TEST(GroundTruthBenchmark, SummaryCountsOverFramesWithATruePose) {
  MethodRun run;
  run.errorPx = {0.5, NAN, 1.5, 7.0, 2.0, NAN, 9.0, INFINITY};
  run.cpuMs = {1.0, 4.0, 2.0, 3.0, 10.0};
  const std::vector<bool> truth = {true, true, true, true, true, true, false, true};
  const MethodSummary s = summarise(run, truth);
  EXPECT_EQ(s.frames, 7);
  EXPECT_EQ(s.posed, 5);
  EXPECT_NEAR(s.coveragePercent(), 100.0 * 5 / 7, 1e-12);
  EXPECT_DOUBLE_EQ(s.meanPx, (0.5 + 1.5 + 7.0 + 2.0) / 4);
  EXPECT_DOUBLE_EQ(s.maxPx, 7.0);
  EXPECT_DOUBLE_EQ(s.p95Px, 2.0 + 0.85 * 5.0);  // sorted 0.5 1.5 2 7: at 0.95 * 3 = 2.85
  EXPECT_EQ(s.behind, 1);
  EXPECT_EQ(s.wrong, 2);
  EXPECT_EQ(s.good, 2);  // 1.5 px counts as good
  EXPECT_DOUBLE_EQ(s.cpuMedianMs, 3.0);
  const MethodSummary none =
      summarise(MethodRun{{}, false, {NAN, NAN}, {}, {}, {}, {}, {}}, {true, true});
  EXPECT_EQ(none.posed, 0);
  EXPECT_TRUE(std::isnan(none.meanPx));
  EXPECT_DOUBLE_EQ(none.coveragePercent(), 0.0);
}

// The predicted error's calibration over the posed frames with a true pose and a prediction:
// true / predicted quartiles, the predictions' median / p95 / max, the frames reported uncertain
// (their mean true error), and the frames more than 5 px off that were not.
TEST(GroundTruthBenchmark, PredictionSummaryComparesTrueWithPredictedErrors) {
  MethodRun run;
  run.errorPx = {0.4, 0.3, NAN, 9.0, 0.2, 0.6, 8.0};
  run.predictedErrorPx = {0.2, 0.3, NAN, 3.0, 0.4, NAN, 2.0};
  run.uncertain = {false, false, false, true, false, false, false};
  const std::vector<bool> truth = {true, true, true, true, false, true, true};
  const PredictionSummary p = summarisePrediction(run, truth);
  EXPECT_EQ(p.frames, 4);  // frames 0, 1, 3, 6 (4: no truth, 5: no prediction, 2: no pose)
  // Ratios 2, 1, 3, 4: median at 1.5 of 0..3 -> 2.5.
  EXPECT_DOUBLE_EQ(p.ratioMedian, 2.5);
  EXPECT_DOUBLE_EQ(p.predictedMedianPx, 1.15);  // sorted 0.2 0.3 2 3: at 1.5
  EXPECT_DOUBLE_EQ(p.predictedMaxPx, 3.0);
  EXPECT_EQ(p.uncertain, 1);
  EXPECT_DOUBLE_EQ(p.uncertainTrueMeanPx, 9.0);
  EXPECT_EQ(p.wrongNotUncertain, 1);  // frame 6: 8 px off, not flagged
  EXPECT_EQ(summarisePrediction(MethodRun{}, truth).frames, 0);
}

TEST(GroundTruthBenchmark, OptionsCheckNamesTheBadOption) {
  GroundTruthBenchmarkOptions o;
  o.references = {0, 40};
  EXPECT_NO_THROW(o.check());
  auto message = [](GroundTruthBenchmarkOptions bad) {
    return test::errorMessage([&] { bad.check(); });
  };
  GroundTruthBenchmarkOptions bad = o;
  bad.references = {3};
  EXPECT_NE(message(bad).find("at least two"), std::string::npos);
  bad.references = {3, 3};
  EXPECT_NE(message(bad).find("frame 3 given twice"), std::string::npos);
  bad = o;
  bad.cubeEdge = 0;
  EXPECT_NE(message(bad).find("--cube-edge"), std::string::npos);
  bad = o;
  bad.methods = {"reftrack", "surf"};
  EXPECT_NE(message(bad).find("unknown method 'surf'"), std::string::npos);
  bad = o;
  bad.passes = 0;
  EXPECT_NE(message(bad).find("--passes"), std::string::npos);
}

// A reference frame needs a true pose, and must be in the sequence: checked before the map.
TEST(GroundTruthBenchmark, ReferenceFramesNeedATruePose) {
  GroundTruthSequence s;
  s.framesDescription = "three frames";
  s.groundTruthDescription = "a ground truth without frame 1";
  s.camera = smallCamera();
  s.frames.assign(3, cv::Mat(480, 752, CV_8UC3, cv::Scalar(80, 80, 80)));
  s.timestamps = {0.0, 0.1, 0.2};
  s.truth = {lookingDown({0, 0, 0}, 0), std::nullopt, lookingDown({0.05, 0, 0}, 0)};
  GroundTruthBenchmarkOptions o;
  o.references = {0, 1};
  std::string m = test::errorMessage(
      [&] { runGroundTruthBenchmark(s, o, TrackerParams{}, ReferencePreparerParams{}); });
  EXPECT_NE(m.find("reference frame 1 has no ground-truth pose (a ground truth without frame 1)"),
            std::string::npos)
      << m;
  o.references = {0, 3};
  m = test::errorMessage(
      [&] { runGroundTruthBenchmark(s, o, TrackerParams{}, ReferencePreparerParams{}); });
  EXPECT_NE(m.find("reference frame 3 is beyond the 3 frames of three frames"), std::string::npos)
      << m;
}

// The benchmark end to end on a short simulated hand-held clip (exact ground truth, 320x240,
// sensor noise SD 2), references frames 0 and 15 (about 17 cm apart), reftrack and the AKAZE
// peer. Each run's errors are those of its poses against the truth (recomputed here), every frame
// is processed once per order and pass, and the peer gives a frame the same pose in either order.
// Measured on this clip (cube error mean / p95 / max): reftrack in sequence order 30/30 frames,
// 0.166 / 0.271 / 0.336 px, shuffled (cold starts) 26/30, 0.074 / 0.189 / 0.198; AKAZE + PnP
// 30/30 in both, 0.130 / 0.254 / 0.398. Bounds: the project's simulator targets for a tracked
// clip (mean 0.5 px; every error below the 1.5 px p95 target), every frame posed in sequence
// order, no pose 5 px off: the margin over the measured figures leaves room for the tracker's
// changes that stay within the targets, while a scoring fault (a wrong cube, the lens applied,
// another frame's truth) or a misregistration is pixels off.
TEST(GroundTruthBenchmark, SimulatedClipErrorsOfReftrackAndAPeer) {
  const auto gl = render::createHeadlessContext();
  SimulationOptions so;
  so.preset = "handheld";
  so.frames = 30;
  so.size = {320, 240};
  SceneSimulator sim(so);
  GroundTruthSequence s;
  s.framesDescription = "simulated handheld";
  s.groundTruthDescription = "the simulator's";
  s.camera = sim.camera();
  for (int k = 0; k < so.frames; ++k) {
    s.frames.push_back(sim.renderFrame(k));
    s.timestamps.push_back(k / so.fps);
    s.truth.push_back(sim.framePose(k));
  }
  GroundTruthBenchmarkOptions o;
  o.references = {0, 15};
  o.methods = {"reftrack", "akaze"};
  o.cubeEdge = 0.1;  // on the marker, the simulator's world origin
  const GroundTruthBenchmarkResult r =
      runGroundTruthBenchmark(s, o, TrackerParams{}, ReferencePreparerParams{});
  EXPECT_EQ(r.frames, 30);
  EXPECT_GT(r.referenceDistancesMm[1], 100.0);
  EXPECT_GT(r.mapPoints, 50);
  ASSERT_EQ(r.modelPoints.size(), 1u);
  EXPECT_EQ(r.modelPoints[0].first, "AKAZE+PnP");
  EXPECT_GT(r.modelPoints[0].second, 50);
  ASSERT_EQ(r.runs.size(), 4u);
  const std::vector<std::pair<std::string, bool>> expected = {
      {"reftrack", false}, {"reftrack", true}, {"AKAZE+PnP", false}, {"AKAZE+PnP", true}};
  const std::vector<Eigen::Vector3d> cube = cubeOn(Eigen::Vector3d::Zero(), 0.1);
  for (std::size_t i = 0; i < r.runs.size(); ++i) {
    const MethodRun& run = r.runs[i];
    EXPECT_EQ(run.method, expected[i].first);
    EXPECT_EQ(run.shuffled, expected[i].second);
    ASSERT_EQ(run.errorPx.size(), 30u);
    EXPECT_EQ(run.cpuMs.size(), 30u);  // one pass
    int noPose = 0;
    for (const auto& [reason, frames] : run.noPose) noPose += frames;
    const MethodSummary sum = summarise(run, r.truth);
    EXPECT_EQ(sum.posed + noPose, 30) << run.method;
    for (std::size_t k = 0; k < 30; ++k) {
      ASSERT_EQ(run.poses[k].has_value(), !std::isnan(run.errorPx[k])) << run.method << " " << k;
      if (!run.poses[k]) continue;
      // The score of this frame's pose against this frame's truth.
      EXPECT_NEAR(run.errorPx[k], cubeErrorPx(s.camera, cube, *s.truth[k], *run.poses[k]), 1e-12);
    }
    std::printf("%s %s: %d/%d posed, cube error mean %.3f, p95 %.3f, max %.3f px\n",
                run.method.c_str(), run.shuffled ? "shuffled" : "sequence", sum.posed, sum.frames,
                sum.meanPx, sum.p95Px, sum.maxPx);
    if (!run.shuffled) {
      EXPECT_EQ(sum.posed, 30) << run.method;
    }
    if (sum.posed == 0) continue;
    EXPECT_LT(sum.meanPx, 0.5) << run.method << (run.shuffled ? " shuffled" : "");
    EXPECT_LT(sum.maxPx, 1.5) << run.method << (run.shuffled ? " shuffled" : "");
    EXPECT_EQ(sum.wrong, 0);
  }
  // reftrack's predicted cube error for every posed frame, none for the peer; the calibration
  // on the simulator is printed (measured: see the commit).
  for (std::size_t k = 0; k < 30; ++k) {
    EXPECT_EQ(std::isnan(r.runs[0].predictedErrorPx[k]), !r.runs[0].poses[k]) << k;
    EXPECT_TRUE(std::isnan(r.runs[2].predictedErrorPx[k])) << k;
  }
  for (const MethodRun& run : {r.runs[0], r.runs[1]}) {
    const PredictionSummary p = summarisePrediction(run, r.truth);
    std::printf("reftrack %s: predicted cube error median %.3f px, true / predicted median %.2f\n",
                run.shuffled ? "shuffled" : "sequence", p.predictedMedianPx, p.ratioMedian);
  }
  // The peer keeps nothing between frames: the same pose for a frame in either order.
  for (std::size_t k = 0; k < 30; ++k)
    if (r.runs[2].poses[k] && r.runs[3].poses[k]) {
      EXPECT_LT(RigidPose::translationDistance(*r.runs[2].poses[k], *r.runs[3].poses[k]), 1e-9);
    }
}

}  // namespace
}  // namespace reftrack::app
