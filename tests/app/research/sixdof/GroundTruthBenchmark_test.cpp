#include "app/research/sixdof/GroundTruthBenchmark.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <opencv2/calib3d.hpp>
#include <set>
#include <utility>

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
  run.plan = planFrames(parseFrameOrder("sequence"), 8, 1);
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
  MethodRun unposed;
  unposed.plan = planFrames(parseFrameOrder("sequence"), 2, 1);
  unposed.errorPx = {NAN, NAN};
  const MethodSummary none = summarise(unposed, {true, true});
  EXPECT_EQ(none.frames, 2);
  EXPECT_EQ(none.posed, 0);
  EXPECT_TRUE(std::isnan(none.meanPx));
  EXPECT_DOUBLE_EQ(none.coveragePercent(), 0.0);
}

// stride:K: only the frames played are scored; the others count neither as frames nor as frames
// without a pose (and an error recorded on one is ignored).
TEST(GroundTruthBenchmark, SummaryScoresOnlyThePlayedFrames) {
  MethodRun run;
  run.order = parseFrameOrder("stride:3");
  run.plan = planFrames(run.order, 8, 1);  // frames 0, 3, 6
  run.errorPx = {0.5, NAN, NAN, 6.0, 0.2, NAN, NAN, NAN};
  const MethodSummary s = summarise(run, std::vector<bool>(8, true));
  EXPECT_EQ(s.frames, 3);
  EXPECT_EQ(s.posed, 2);
  EXPECT_EQ(s.wrong, 1);
  EXPECT_EQ(s.good, 1);  // frame 4's 0.2 px is not played: not scored
  EXPECT_DOUBLE_EQ(s.meanPx, (0.5 + 6.0) / 2);
}

// Per cut: the frames either side, the frames after the cut before the first pose within 1.5 px
// (0: the first after the cut), and the poses more than 5 px off until the next cut.
TEST(GroundTruthBenchmark, CutRecoveriesCountFramesToReacquireAndWrongPoses) {
  MethodRun run;
  run.order = parseFrameOrder("cuts:3");
  run.plan.frames = {6, 7, 8, 0, 1, 2, 3, 4, 5};
  run.plan.cuts = {3, 6};
  //            frame:  0    1    2    3    4    5    6    7    8
  run.errorPx = {9.0, NAN, 1.4, 0.3, 0.2, 0.1, 2.0, 0.5, 0.4};
  std::vector<CutRecovery> cuts = cutRecoveries(run);
  ASSERT_EQ(cuts.size(), 2u);
  EXPECT_EQ(cuts[0].position, 3u);
  EXPECT_EQ(cuts[0].fromFrame, 8);
  EXPECT_EQ(cuts[0].toFrame, 0);
  EXPECT_EQ(cuts[0].segmentFrames, 3);
  EXPECT_EQ(cuts[0].framesToReacquire, 2);  // 9 px (wrong), no pose, then 1.4 px
  EXPECT_EQ(cuts[0].wrong, 1);
  EXPECT_EQ(cuts[1].fromFrame, 2);
  EXPECT_EQ(cuts[1].toFrame, 3);
  EXPECT_EQ(cuts[1].framesToReacquire, 0);
  EXPECT_EQ(cuts[1].wrong, 0);
  // Never within 1.5 px in the segment: -1.
  run.errorPx[0] = run.errorPx[2] = 6.0;
  cuts = cutRecoveries(run);
  EXPECT_EQ(cuts[0].framesToReacquire, -1);
  EXPECT_EQ(cuts[0].wrong, 2);
  // No cuts in the other orders.
  run.plan = planFrames(parseFrameOrder("shuffled-sequence"), 9, 1);
  EXPECT_TRUE(cutRecoveries(run).empty());
}

// A stand-in tracker that carries state between frames: it answers each frame with the true pose
// of the frame it saw before (nothing after a start or a cold start), as a tracker that keeps its
// last pose would. It records what it was asked.
class LaggingMethod final : public PoseMethod {
 public:
  explicit LaggingMethod(const GroundTruthSequence& s) : s_(s) {}
  std::string name() const override { return "lagging"; }
  void startRun() override {
    ++starts;
    last_.reset();
  }
  void coldStart() override {
    ++coldStarts;
    last_.reset();
  }
  std::optional<RigidPose> locate(const cv::Mat& frame, std::string& reason) override {
    const int k = frame.at<unsigned char>(0, 0);  // the frames are filled with their index
    seen.push_back(k);
    const std::optional<RigidPose> answer = last_;
    last_ = s_.truth[static_cast<std::size_t>(k)];
    if (!answer) reason = "no earlier frame";
    return answer;
  }
  int starts = 0, coldStarts = 0;
  std::vector<int> seen;

 private:
  const GroundTruthSequence& s_;
  std::optional<RigidPose> last_;
};

// 40 frames in 4 views of 10: 0.05 mm between frames of a view (under 1 px across a view), 3 cm
// between views (tens of px). Frame k is a small image filled with k.
GroundTruthSequence fourViews() {
  GroundTruthSequence s;
  s.framesDescription = "four views";
  s.groundTruthDescription = "made up";
  s.camera = smallCamera();
  for (int k = 0; k < 40; ++k) {
    s.frames.emplace_back(4, 4, CV_8UC1, cv::Scalar(k));
    s.timestamps.push_back(k / 30.0);
    s.truth.push_back(lookingDown({0.00005 * k + 0.03 * (k / 10), 0, 0}, 0));
  }
  return s;
}

MethodRun playedRun(const std::string& order, int frames) {
  MethodRun run;
  run.order = parseFrameOrder(order);
  run.plan = planFrames(run.order, frames, 3);
  run.errorPx.assign(static_cast<std::size_t>(frames), NAN);
  run.poses.resize(static_cast<std::size_t>(frames));
  return run;
}

// Only `shuffled` resets the method between frames: shuffled-sequence plays the same frames in
// the same order as one run, so a method carrying its state gives a (lagging) pose on every frame
// after the first, and after each jump between views a confidently wrong one.
TEST(GroundTruthBenchmark, OnlyTheShuffledOrderResetsBetweenFrames) {
  const GroundTruthSequence s = fourViews();
  const std::vector<Eigen::Vector3d> cube = cubeOn({0.16, -0.10, 0.0}, 0.1);
  const std::vector<bool> truth(40, true);
  MethodRun cold = playedRun("shuffled", 40), warm = playedRun("shuffled-sequence", 40);
  LaggingMethod coldMethod(s), warmMethod(s);
  playFrames(coldMethod, s, cube, true, cold);
  playFrames(warmMethod, s, cube, true, warm);
  EXPECT_EQ(coldMethod.starts, 1);
  EXPECT_EQ(coldMethod.coldStarts, 40);
  EXPECT_EQ(warmMethod.starts, 1);
  EXPECT_EQ(warmMethod.coldStarts, 0);
  EXPECT_EQ(coldMethod.seen, cold.plan.frames);
  EXPECT_EQ(warmMethod.seen, cold.plan.frames);  // the same order
  EXPECT_EQ(cold.cpuMs.size(), 40u);
  const MethodSummary c = summarise(cold, truth), w = summarise(warm, truth);
  EXPECT_EQ(c.posed, 0);
  EXPECT_EQ(cold.noPose.at("no earlier frame"), 40);
  EXPECT_EQ(w.posed, 39);
  // Each posed frame's error is that of the frame played before it, against this one's truth.
  int jumps = 0;
  for (std::size_t i = 1; i < warm.plan.frames.size(); ++i) {
    const int k = warm.plan.frames[i], before = warm.plan.frames[i - 1];
    jumps += k / 10 != before / 10 ? 1 : 0;
    EXPECT_NEAR(warm.errorPx[static_cast<std::size_t>(k)],
                cubeErrorPx(s.camera, cube, *s.truth[static_cast<std::size_t>(k)],
                            *s.truth[static_cast<std::size_t>(before)]),
                1e-12);
  }
  EXPECT_GT(jumps, 20);  // a shuffle of 40 frames in 4 views changes view most of the time
  EXPECT_EQ(w.wrong, jumps);
  EXPECT_EQ(w.good, 39 - jumps);
  // A second pass plays again (timing) but scores nothing new.
  playFrames(warmMethod, s, cube, false, warm);
  EXPECT_EQ(warmMethod.starts, 2);
  EXPECT_EQ(warm.cpuMs.size(), 80u);
  EXPECT_EQ(summarise(warm, truth).posed, 39);
}

// cuts:4 over the four views: one sequence, no reset; after each cut the lagging method is wrong
// once (it still holds the other view's pose) and good from the next frame (re-acquired within
// 1). stride:3 gives it only frames 0, 3, ..., 39, and only those are scored.
TEST(GroundTruthBenchmark, CutsAndStridePlayOneSequence) {
  const GroundTruthSequence s = fourViews();
  const std::vector<Eigen::Vector3d> cube = cubeOn({0.16, -0.10, 0.0}, 0.1);
  const std::vector<bool> truth(40, true);
  MethodRun cuts = playedRun("cuts:4", 40);
  LaggingMethod method(s);
  playFrames(method, s, cube, true, cuts);
  EXPECT_EQ(method.coldStarts, 0);
  EXPECT_EQ(method.seen, cuts.plan.frames);
  const std::vector<CutRecovery> recoveries = cutRecoveries(cuts);
  ASSERT_EQ(recoveries.size(), 3u);
  for (const CutRecovery& r : recoveries) {
    EXPECT_EQ(r.segmentFrames, 10);
    EXPECT_EQ(r.toFrame % 10, 0);  // a segment is a view
    EXPECT_EQ(r.framesToReacquire, 1);
    EXPECT_EQ(r.wrong, 1);
  }
  const MethodSummary c = summarise(cuts, truth);
  EXPECT_EQ(c.frames, 40);
  EXPECT_EQ(c.posed, 39);
  EXPECT_EQ(c.wrong, 3);

  MethodRun stride = playedRun("stride:3", 40);
  LaggingMethod strided(s);
  playFrames(strided, s, cube, true, stride);
  std::vector<int> expected;
  for (int k = 0; k < 40; k += 3) expected.push_back(k);
  EXPECT_EQ(strided.seen, expected);
  EXPECT_EQ(strided.coldStarts, 0);
  EXPECT_EQ(stride.cpuMs.size(), expected.size());
  const MethodSummary st = summarise(stride, truth);
  EXPECT_EQ(st.frames, 14);  // played frames only: unplayed ones are not "not posed"
  EXPECT_EQ(st.posed, 13);
  EXPECT_EQ(stride.noPose.at("no earlier frame"), 1);
  EXPECT_EQ(st.wrong, 3);  // 9 -> 12, 18 -> 21, 27 -> 30: another view
  for (int k = 0; k < 40; ++k)
    if (k % 3 != 0) {
      EXPECT_TRUE(std::isnan(stride.errorPx[static_cast<std::size_t>(k)])) << k;
    }
}

// A stand-in for a tracker that loses the mapped view (frames 0-9 of fourViews) and comes back:
// in it, the true pose from its second frame on (the first is refused by the inlier spread);
// elsewhere no pose (PnP inliers), except frame 22 where it gives frame 0's pose (wrong).
class ReturningMethod final : public PoseMethod {
 public:
  explicit ReturningMethod(const GroundTruthSequence& s) : s_(s) {}
  std::string name() const override { return "returning"; }
  void startRun() override { inView_ = false; }
  void coldStart() override { inView_ = false; }
  std::optional<RigidPose> locate(const cv::Mat& frame, std::string& reason) override {
    const int k = frame.at<unsigned char>(0, 0);
    const bool wasInView = std::exchange(inView_, k < 10);
    start_ = search_ = RecoveryStage::None;
    if (k == 22) return s_.truth[0];
    if (k < 10 && wasInView) return s_.truth[static_cast<std::size_t>(k)];
    start_ = RecoveryStage::StartNoPose;
    search_ = k < 10 ? RecoveryStage::InlierSpread : RecoveryStage::PnpInliers;
    reason = "lost";
    return std::nullopt;
  }
  RecoveryStage lastStart() const override { return start_; }
  RecoveryStage lastSearch() const override { return search_; }
  double lastSearchCpuMs() const override { return 1.0; }

 private:
  const GroundTruthSequence& s_;
  bool inView_ = false;
  RecoveryStage start_ = RecoveryStage::None, search_ = RecoveryStage::None;
};

// return:0-4+20-24+4-0 plays frame 0-4 twice: each play is scored on its own, per range the
// plays to the first pose within 5 px are counted, and the stops of every lost frame are counted
// by stage (scored pass only).
TEST(GroundTruthBenchmark, ReturnOrdersAreScoredPerPlayAndPerRange) {
  const GroundTruthSequence s = fourViews();
  const std::vector<Eigen::Vector3d> cube = cubeOn({0.16, -0.10, 0.0}, 0.1);
  const std::vector<bool> truth(40, true);
  MethodRun run = playedRun("return:0-4+20-24+4-0", 40);
  ReturningMethod method(s);
  playFrames(method, s, cube, true, run);
  ASSERT_EQ(run.playedErrorPx.size(), 15u);
  EXPECT_EQ(std::count(run.playedScored.begin(), run.playedScored.end(), true), 15);
  EXPECT_TRUE(std::isnan(run.playedErrorPx[0]));
  EXPECT_LT(run.playedErrorPx[1], 1e-9);
  EXPECT_GT(run.playedErrorPx[7], kWrongPosePx);  // frame 22: frame 0's pose, 3 views off
  EXPECT_TRUE(std::isnan(run.errorPx[4]));        // its last play (the return's first) has none
  const MethodSummary sum = summarise(run, truth);
  EXPECT_EQ(sum.frames, 15);
  EXPECT_EQ(sum.posed, 9);
  EXPECT_EQ(sum.wrong, 1);
  const std::vector<RangeOutcome> ranges = rangeOutcomes(run, 20.0);
  ASSERT_EQ(ranges.size(), 3u);
  const int posed[] = {4, 1, 4}, within[] = {4, 0, 4}, wrong[] = {0, 1, 0}, k[] = {1, -1, 1};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(ranges[i].frames, 5) << i;
    EXPECT_EQ(ranges[i].posed, posed[i]) << i;
    EXPECT_EQ(ranges[i].within, within[i]) << i;
    EXPECT_EQ(ranges[i].wrong, wrong[i]) << i;
    EXPECT_EQ(ranges[i].framesToReacquire, k[i]) << i;
    EXPECT_FALSE(std::isnan(ranges[i].cpuMeanMs)) << i;
  }
  EXPECT_EQ(ranges[2].range, (FrameRange{4, 0}));
  EXPECT_EQ(run.startStops, (std::map<std::string, int>{{"no start pose", 6}}));
  EXPECT_EQ(run.searchStops,
            (std::map<std::string, int>{{"inlier spread", 2}, {"PnP inliers", 4}}));
  EXPECT_EQ(run.searchCpuMs, std::vector<double>(6, 1.0));
  // A second (timing) pass counts no stops.
  playFrames(method, s, cube, false, run);
  EXPECT_EQ(run.searchStops.at("PnP inliers"), 4);
  EXPECT_EQ(run.cpuMs.size(), 30u);
  EXPECT_TRUE(rangeOutcomes(playedRun("sequence", 40), 20.0).empty());
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
  bad = o;
  bad.orders = {"sequence", "cuts:1"};
  EXPECT_NE(message(bad).find("--order: 'cuts:1'"), std::string::npos);
  bad.orders = {};
  EXPECT_NE(message(bad).find("--order names no order"), std::string::npos);
}

// The cube in front of a reference: centred `distance` along that camera's optical axis (its
// centre projects to the principal point), its edges along the camera's axes; scoringCube takes
// the first reference's true pose, and names the input's frame when it has none.
TEST(GroundTruthBenchmark, CubeInFrontOfTheReferenceStandsOnItsOpticalAxis) {
  const RigidPose reference = lookingDown({0.02, -0.03, 0.1}, 0.4);
  const std::vector<Eigen::Vector3d> cube = cubeInFrontOf(reference, 1.0, 0.08);
  ASSERT_EQ(cube.size(), 8u);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : cube) {
    const Eigen::Vector3d c = reference * v;  // in the reference camera's frame
    EXPECT_NEAR(std::abs(c.x()), 0.04, 1e-12);
    EXPECT_NEAR(std::abs(c.y()), 0.04, 1e-12);
    EXPECT_NEAR(std::abs(c.z() - 1.0), 0.04, 1e-12);
    centre += c / 8.0;
  }
  const Eigen::Vector2d principal = smallCamera().project(centre);
  EXPECT_NEAR(principal.x(), 355.2, 1e-9);
  EXPECT_NEAR(principal.y(), 250.3, 1e-9);

  GroundTruthSequence s;
  s.firstFrame = 200;
  s.truth = {std::nullopt, reference};
  GroundTruthBenchmarkOptions o;
  o.references = {1, 0};
  o.cubeEdge = 0.08;
  o.cubeInFrontM = 1.0;
  const std::vector<Eigen::Vector3d> scored = scoringCube(o, s);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_LT((scored[i] - cube[i]).norm(), 1e-15) << i;
  o.references = {0, 1};
  const std::string m = test::errorMessage([&] { scoringCube(o, s); });
  EXPECT_NE(m.find("in front of reference frame 200, which has no true pose"), std::string::npos)
      << m;
  o.cubeInFrontM = 0.0;  // on the world's z = 0 plane instead
  o.cubeCentre = {0.1, 0.2, 0.0};
  EXPECT_EQ(scoringCube(o, s), cubeOn({0.1, 0.2, 0.0}, 0.08));
  o.cubeInFrontM = 0.03;  // reaching behind the camera
  EXPECT_NE(test::errorMessage([&] { o.check(); }).find("reaches behind the camera"),
            std::string::npos);
}

// Replayed peers and a refused map (`bench-real --suite`): the peer's poses, given once by
// options.peerPoses, score every order alike (its CPU times counted once per order); a map the
// preparation refuses (blank frames) leaves reftrack without a pose on every frame, the reason
// given, instead of ending the benchmark.
TEST(GroundTruthBenchmark, ReplayedPeersAndARefusedMap) {
  GroundTruthSequence s;
  s.framesDescription = "blank frames";
  s.groundTruthDescription = "made up";
  s.camera = smallCamera();
  s.firstFrame = 10;
  for (int k = 0; k < 4; ++k) {
    const double grey = 80 + 10 * k;  // blank, but not the same image twice
    s.frames.emplace_back(480, 752, CV_8UC3, cv::Scalar(grey, grey, grey));
    s.timestamps.push_back((10 + k) / 30.0);
    s.truth.push_back(lookingDown({0.01 * k, 0, 0}, 0));
  }
  s.truth[3].reset();  // no true pose: not scored
  GroundTruthBenchmarkOptions o;
  o.references = {0, 2};
  o.methods = {"reftrack", "sift"};
  o.orders = {"sequence", "shuffled-sequence"};
  o.mapFailureIsLoss = true;
  int calls = 0;
  o.peerPoses = [&](const std::string& detector, const std::vector<int>& references) {
    ++calls;
    EXPECT_EQ(detector, "sift");
    EXPECT_EQ(references, o.references);
    PeerPoses p;
    p.method = "SIFT+PnP";
    p.modelPoints = 321;
    p.poses = {s.truth[0], std::nullopt, lookingDown({0.023, 0.001, 0}, 0.002), s.truth[0]};
    p.reasons = {"", "too few PnP inliers", "", ""};
    p.cpuMs = {1.0, 2.0, 3.0, 4.0};
    return p;
  };
  const GroundTruthBenchmarkResult r =
      runGroundTruthBenchmark(s, o, TrackerParams{}, ReferencePreparerParams{});
  EXPECT_EQ(calls, 1);
  EXPECT_NE(r.mapError.find("map points"), std::string::npos) << r.mapError;
  EXPECT_EQ(r.firstFrame, 10);
  ASSERT_EQ(r.modelPoints.size(), 1u);
  EXPECT_EQ(r.modelPoints[0], (std::pair<std::string, int>{"SIFT+PnP", 321}));
  ASSERT_EQ(r.runs.size(), 4u);
  const std::vector<Eigen::Vector3d> cube = cubeOn(Eigen::Vector3d::Zero(), 0.1);
  const double third =
      cubeErrorPx(s.camera, cube, *s.truth[2], lookingDown({0.023, 0.001, 0}, 0.002));
  EXPECT_GT(third, 1.0);
  for (const MethodRun& run : r.runs) {
    if (run.method == "reftrack") {
      ASSERT_EQ(run.noPose.size(), 1u) << run.order.name;
      EXPECT_EQ(run.noPose.begin()->first, "no map: " + r.mapError);
      EXPECT_EQ(run.noPose.begin()->second, 3);  // the frames with a true pose
      EXPECT_EQ(summarise(run, r.truth).posed, 0);
      continue;
    }
    EXPECT_EQ(run.method, "SIFT+PnP");
    EXPECT_DOUBLE_EQ(run.errorPx[0], 0.0) << run.order.name;
    EXPECT_TRUE(std::isnan(run.errorPx[1]));
    EXPECT_DOUBLE_EQ(run.errorPx[2], third);
    EXPECT_TRUE(std::isnan(run.errorPx[3]));  // posed, but no truth to score it against
    ASSERT_TRUE(run.poses[3]);
    EXPECT_EQ(run.noPose, (std::map<std::string, int>{{"too few PnP inliers", 1}}));
    std::vector<double> cpu = run.cpuMs;
    std::sort(cpu.begin(), cpu.end());
    EXPECT_EQ(cpu, (std::vector<double>{1.0, 2.0, 3.0, 4.0})) << run.order.name;
  }
  // The order the peer replays in is the order's own.
  EXPECT_EQ(r.runs[3].plan.frames, planFrames(parseFrameOrder("shuffled-sequence"), 4, 1).frames);
  // Without mapFailureIsLoss the refusal ends the benchmark; replayed peers take no away:N order.
  o.mapFailureIsLoss = false;
  EXPECT_NE(test::errorMessage([&] {
              runGroundTruthBenchmark(s, o, TrackerParams{}, ReferencePreparerParams{});
            }).find("map points"),
            std::string::npos);
  o.orders = {"away:2"};
  o.awayDescription = "elsewhere";
  EXPECT_NE(test::errorMessage([&] { o.check(); }).find("replayed poses cover the sequence's"),
            std::string::npos);
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
  const std::vector<std::pair<std::string, std::string>> expected = {{"reftrack", "sequence"},
                                                                     {"reftrack", "shuffled"},
                                                                     {"AKAZE+PnP", "sequence"},
                                                                     {"AKAZE+PnP", "shuffled"}};
  const std::vector<Eigen::Vector3d> cube = cubeOn(Eigen::Vector3d::Zero(), 0.1);
  for (std::size_t i = 0; i < r.runs.size(); ++i) {
    const MethodRun& run = r.runs[i];
    EXPECT_EQ(run.method, expected[i].first);
    EXPECT_EQ(run.order.name, expected[i].second);
    const bool shuffled = run.order.kind == FrameOrderKind::Shuffled;
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
                run.method.c_str(), run.order.name.c_str(), sum.posed, sum.frames, sum.meanPx,
                sum.p95Px, sum.maxPx);
    if (!shuffled) {
      EXPECT_EQ(sum.posed, 30) << run.method;
    }
    if (sum.posed == 0) continue;
    EXPECT_LT(sum.meanPx, 0.5) << run.method << " " << run.order.name;
    EXPECT_LT(sum.maxPx, 1.5) << run.method << " " << run.order.name;
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
                run.order.name.c_str(), p.predictedMedianPx, p.ratioMedian);
  }
  // The peer keeps nothing between frames: the same pose for a frame in either order.
  for (std::size_t k = 0; k < 30; ++k)
    if (r.runs[2].poses[k] && r.runs[3].poses[k]) {
      EXPECT_LT(RigidPose::translationDistance(*r.runs[2].poses[k], *r.runs[3].poses[k]), 1e-9);
    }
}

}  // namespace
}  // namespace reftrack::app
