#include "app/viewer/HomographyFrameTracker.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <opencv2/imgproc.hpp>

#include "ErrorMessage.hpp"
#include "app/research/homography/HomographyGroundTruth.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "engine/core/Error.hpp"
#include "engine/homography/HomographyDlt.hpp"
#include "render/context/GlContext.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

// The simulator's slow pan (preset rotate over 400 frames: ~0.6 deg per frame at the start),
// 320x240, 60 degree field of view, optional motion blur; frames k >= 0 from reference A.
struct PanSequence {
  explicit PanSequence(bool blur) {
    SimulationOptions o;
    o.preset = "rotate";
    o.frames = 400;
    o.size = {320, 240};
    o.blur = blur;
    sim = std::make_unique<SceneSimulator>(o);
  }
  cv::Matx33d truth(int k) const {
    const RigidPose aToK = sim->framePose(k) * sim->referencePoseA().inverse();
    return rotationHomography(sim->camera().K(), aToK.rotation());
  }
  std::unique_ptr<SceneSimulator> sim;
};

class HomographyFrameTrackerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { context_ = render::createHeadlessContext().release(); }
  static void TearDownTestSuite() { delete context_; }
  static render::GlContext* context_;
};
render::GlContext* HomographyFrameTrackerTest::context_ = nullptr;

}  // namespace

TEST_F(HomographyFrameTrackerTest, ResultCarriesInverseHRotationPoseAndMappedLabels) {
  PanSequence seq(false);
  const cv::Mat reference = seq.sim->renderReference('A');
  const AnnotationSet labels({{"centre", {159.5, 119.5}}, {"left", {40, 60}}});
  HomographyFrameTracker tracker(reference, TrackerParams{}, seq.sim->camera(), labels);
  EXPECT_EQ(tracker.name(), "homography");
  for (int k = 0; k < 6; ++k) {
    const TrackingResult r = tracker.process(seq.sim->renderFrame(k), k, k / 30.0);
    ASSERT_EQ(r.status, "tracking") << k;
    ASSERT_TRUE(r.H && r.worldToCamera);
    const cv::Matx33d truth = seq.truth(k);
    // TrackingResult::H is frame -> reference: its product with the tracker's H is identity.
    const cv::Matx33d product = *r.H * tracker.last().H;
    EXPECT_LT(cv::norm(product * (1.0 / product(2, 2)) - cv::Matx33d::eye()), 1e-9);
    // Rotation from H = K R K^-1 within 0.15 deg of the truth: ~0.3 px of registration error
    // over a 277 px focal length is 0.06 deg, and the perspective row of H amplifies it
    // (measured up to 0.08 deg).
    const Eigen::Matrix3d Rtrue =
        (seq.sim->framePose(k) * seq.sim->referencePoseA().inverse()).rotation();
    const double angle = Eigen::AngleAxisd(r.worldToCamera->rotation() * Rtrue.transpose()).angle();
    EXPECT_LT(angle * 180 / M_PI, 0.15) << k;
    EXPECT_TRUE(r.worldToCamera->translation().isZero());
    ASSERT_EQ(tracker.mappedLabels().size(), 2u);
    const cv::Point2d q = tracker.mappedLabels()[0];
    const cv::Point2d t = transferPoint(truth, {159.5, 119.5});
    EXPECT_LT(std::hypot(q.x - t.x, q.y - t.y), 0.5) << k;  // the < 0.5 px annotation target
    EXPECT_EQ(r.debug.corners.size(), tracker.last().frameCorners.size());
    EXPECT_EQ(static_cast<int>(r.debug.matches.size()), r.inliers);
    // corners, prediction, matching, robust fit, keypoints, refine, verify
    EXPECT_EQ(r.stages.size(), 7u);
  }
}

// Through a k1 = -0.3 lens (320x240, 50 degrees) the pan is no homography between the recorded
// frames; undistorted it is K R K^-1 again. The labels, mapped through the lens, land where the
// lens puts them (projectDistorted of the true ray): the centre label within the 0.5 px
// annotation target, the labels near the image corners, where an error of H grows with the
// distance from the matched texture, within 1 px (measured 0.83), and the debug corners are
// back in the recorded frame.
TEST_F(HomographyFrameTrackerTest, RegistersThroughALensAndMapsLabelsBackOntoIt) {
  SimulationOptions o;
  o.preset = "rotate";
  o.frames = 400;
  o.size = {320, 240};
  o.fovDeg = 50.0;
  o.distortion = {-0.3, 0.0, 0.0, 0.0};
  SceneSimulator sim(o);
  const PinholeCamera& camera = sim.camera();
  const std::vector<cv::Point2d> at = {{159.5, 119.5}, {30, 25}, {290, 215}, {295, 30}};
  std::vector<Annotation> list;
  for (const cv::Point2d& p : at) list.push_back({"l", p});
  HomographyFrameTracker tracker(sim.renderReference('A'), TrackerParams{}, camera,
                                 AnnotationSet(list));
  std::vector<cv::Point2f> recorded;
  for (const cv::Point2d& p : at)
    recorded.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
  const std::vector<cv::Point2f> rays = camera.undistortPixels(recorded);
  double worst = 0.0, worstCentre = 0.0;
  int checked = 0;
  for (int k = 0; k < 8; ++k) {
    const TrackingResult r = tracker.process(sim.renderFrame(k), k, k / 30.0);
    ASSERT_EQ(r.status, "tracking") << k;
    const Eigen::Matrix3d R = (sim.framePose(k) * sim.referencePoseA().inverse()).rotation();
    ASSERT_EQ(tracker.mappedLabels().size(), at.size());
    for (std::size_t i = 0; i < at.size(); ++i) {
      const Eigen::Vector3d ray = camera.K().inverse() * Eigen::Vector3d(rays[i].x, rays[i].y, 1);
      const Eigen::Vector2d truth = camera.projectDistorted(R * ray);
      if (truth.x() < 0 || truth.y() < 0 || truth.x() > 319 || truth.y() > 239) continue;
      const cv::Point2d q = tracker.mappedLabels()[i];
      const double error = std::hypot(q.x - truth.x(), q.y - truth.y());
      worst = std::max(worst, error);
      if (i == 0) worstCentre = std::max(worstCentre, error);
      ++checked;
    }
    for (const cv::Point2f& c : r.debug.corners) {
      EXPECT_GE(c.x, -0.5f);
      EXPECT_LE(c.x, 319.5f);
    }
  }
  std::cout << checked << " labels through the lens: worst error " << worst << " px, centre "
            << worstCentre << " px\n";
  EXPECT_GE(checked, 24);
  EXPECT_LT(worstCentre, 0.5);
  EXPECT_LT(worst, 1.0);
}

TEST_F(HomographyFrameTrackerTest, ApplyParamsRebuildsOrRejects) {
  PanSequence seq(false);
  HomographyFrameTracker tracker(seq.sim->renderReference('A'), TrackerParams{});
  TrackerParams p;
  p.ransac.maxIterations = 200;
  p.correlation.minScore = 0.7;
  tracker.applyParams(p);
  EXPECT_EQ(tracker.process(seq.sim->renderFrame(0), 0, 0).status, "tracking");
  p.ransac.minInlierRatio = 2.0;
  EXPECT_THROW(tracker.applyParams(p), Error);
  EXPECT_EQ(tracker.process(seq.sim->renderFrame(1), 1, 0).status, "tracking");
  // A camera of another size than the reference is the frames' camera (the reference is a
  // picture from another one): accepted, and a frame not of its size is refused by name.
  HomographyFrameTracker other(seq.sim->renderReference('A'), TrackerParams{},
                               PinholeCamera::fromFieldOfView({640, 480}, 60));
  EXPECT_FALSE(other.referenceSharesCamera());
  const std::string message =
      test::errorMessage([&] { other.process(seq.sim->renderFrame(2), 2, 0); });
  EXPECT_NE(message.find("calibrated for 640x480"), std::string::npos) << message;
}

// Robustness target (issue 4): sequences with motion blur, a +-30% brightness change or a
// passing occluder do not crash, failed frames are flagged, and tracking is back within 5 frames
// after the view is clear. Runs the first 25 frames of the slow pan (up to ~15 degrees) with the
// perturbation on some frames (blur: every frame) and records each frame's outcome.
enum class Perturbation { Blur, Brightness, Occluder };

struct FrameOutcome {
  bool affected = false;
  bool tracked = false;
  double cornerErrorPx = 0;  // at the frame corners (tracked frames)
};

constexpr int kOccluderFirst = 10, kOccluderLast = 17;

std::vector<FrameOutcome> runPerturbed(Perturbation what) {
  PanSequence seq(what == Perturbation::Blur);
  HomographyFrameTracker tracker(seq.sim->renderReference('A'), TrackerParams{});
  std::vector<FrameOutcome> out;
  for (int k = 0; k < 25; ++k) {
    cv::Mat frame = seq.sim->renderFrame(k);
    FrameOutcome o;
    o.affected = what == Perturbation::Blur;
    if (what == Perturbation::Brightness && k >= 8 && k <= 17) {
      frame.convertTo(frame, -1, k <= 12 ? 1.3 : 0.7);  // +30% (saturating), then -30%
      o.affected = true;
    }
    if (what == Perturbation::Occluder && k >= kOccluderFirst && k <= kOccluderLast) {
      // A dark bar a quarter of the frame wide crossing from left to right.
      const int x = (k - kOccluderFirst) * frame.cols / 7 - frame.cols / 8;
      cv::rectangle(frame, cv::Rect(x, 0, frame.cols / 4, frame.rows), cv::Scalar(40, 40, 40),
                    cv::FILLED);
      o.affected = true;
    }
    const TrackingResult r = tracker.process(frame, k, k / 30.0);
    // A failed frame is flagged as such, never reported as tracked with a stale pose.
    EXPECT_TRUE(r.status == "tracking" || r.status.rfind("lost", 0) == 0) << k << ": " << r.status;
    o.tracked = r.status == "tracking";
    EXPECT_TRUE(o.tracked || !r.H.has_value()) << k;  // a lost frame carries no stale H
    if (o.tracked) o.cornerErrorPx = frameCornerError(tracker.last().H, seq.truth(k), frame.size());
    out.push_back(o);
  }
  return out;
}

int lostUnaffected(const std::vector<FrameOutcome>& f) {
  int n = 0;
  for (const FrameOutcome& o : f) n += (!o.affected && !o.tracked) ? 1 : 0;
  return n;
}
int trackedCount(const std::vector<FrameOutcome>& f) {
  int n = 0;
  for (const FrameOutcome& o : f) n += o.tracked ? 1 : 0;
  return n;
}
double worstError(const std::vector<FrameOutcome>& f) {
  double w = 0;
  for (const FrameOutcome& o : f) w = std::max(w, o.cornerErrorPx);
  return w;
}

TEST_F(HomographyFrameTrackerTest, SurvivesABrightnessChange) {
  const std::vector<FrameOutcome> f = runPerturbed(Perturbation::Brightness);
  EXPECT_EQ(lostUnaffected(f), 0);
  EXPECT_EQ(trackedCount(f), 25);  // measured: NCC absorbs the gain, every frame registers
  // At the frame corners (the worst place, extrapolated from the matched area): measured 0.57 px
  // worst. (It was 1.72 px on the -30% frames while the corner detector kept the FAST threshold
  // of the brighter frames and found only 39-48 of its 110 corners.)
  EXPECT_LT(worstError(f), 1.0);
}

TEST_F(HomographyFrameTrackerTest, SurvivesAPassingOccluder) {
  const std::vector<FrameOutcome> f = runPerturbed(Perturbation::Occluder);
  EXPECT_EQ(lostUnaffected(f), 0);
  // Back within 5 frames after the view is clear: the first clear frame already (measured).
  for (int k = kOccluderLast + 1; k < std::min<int>(kOccluderLast + 6, f.size()); ++k)
    EXPECT_TRUE(f[static_cast<size_t>(k)].tracked) << k;
  // Measured 24 of 25: only the frame where the bar covers the most reference corners is lost.
  EXPECT_GE(trackedCount(f), 22);
  EXPECT_LT(worstError(f), 1.0);
}

TEST_F(HomographyFrameTrackerTest, TracksThroughMotionBlur) {
  const std::vector<FrameOutcome> f = runPerturbed(Perturbation::Blur);
  // Blur over the whole sequence: measured 25 of 25 registered; the smeared corners cost
  // accuracy: measured 0.80 px worst at the frame corners.
  EXPECT_GE(trackedCount(f), 22);
  EXPECT_LT(worstError(f), 1.5);
}
