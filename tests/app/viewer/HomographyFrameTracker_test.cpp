#include "app/viewer/HomographyFrameTracker.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "app/homography/HomographyGroundTruth.hpp"
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
    EXPECT_EQ(r.stages.size(), 4u);
  }
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
  EXPECT_THROW(HomographyFrameTracker(seq.sim->renderReference('A'), TrackerParams{},
                                      PinholeCamera::fromFieldOfView({640, 480}, 60)),
               Error);
}

// Robustness target: sequences with motion blur, a +-30% brightness change or a passing occluder
// lose tracking on the affected frames at most. Runs the first 25 frames of the slow pan (up to
// ~15 degrees; further on, the matches to the reference thin out towards the 35% rule even
// unperturbed) with the perturbation on some frames (blur: every frame) and returns the number
// of unaffected frames lost; `worst` gets the largest corner error of the registered frames.
enum class Perturbation { Blur, Brightness, Occluder };

int lostOutsidePerturbation(Perturbation what, int& tracked, double& worst) {
  PanSequence seq(what == Perturbation::Blur);
  HomographyFrameTracker tracker(seq.sim->renderReference('A'), TrackerParams{});
  int lostUnaffected = 0;
  tracked = 0;
  worst = 0;
  for (int k = 0; k < 25; ++k) {
    cv::Mat frame = seq.sim->renderFrame(k);
    bool affected = what == Perturbation::Blur;
    if (what == Perturbation::Brightness && k >= 8 && k <= 17) {
      frame.convertTo(frame, -1, k <= 12 ? 1.3 : 0.7);  // +30% (saturating), then -30%
      affected = true;
    }
    if (what == Perturbation::Occluder && k >= 10 && k <= 17) {
      // A dark bar a quarter of the frame wide crossing from left to right.
      const int x = (k - 10) * frame.cols / 7 - frame.cols / 8;
      cv::rectangle(frame, cv::Rect(x, 0, frame.cols / 4, frame.rows), cv::Scalar(40, 40, 40),
                    cv::FILLED);
      affected = true;
    }
    const TrackingResult r = tracker.process(frame, k, k / 30.0);
    if (r.status != "tracking") {
      if (!affected) ++lostUnaffected;
      continue;
    }
    ++tracked;
    worst = std::max(worst, frameCornerError(tracker.last().H, seq.truth(k), frame.size()));
  }
  return lostUnaffected;
}

TEST_F(HomographyFrameTrackerTest, SurvivesABrightnessChange) {
  int tracked = 0;
  double worst = 0;
  EXPECT_EQ(lostOutsidePerturbation(Perturbation::Brightness, tracked, worst), 0);
  EXPECT_EQ(tracked, 25);  // measured: NCC absorbs the gain, every frame registers
  EXPECT_LT(worst, 1.0);   // the paper's < 1 px, at the frame corners (the worst place)
}

TEST_F(HomographyFrameTrackerTest, SurvivesAPassingOccluder) {
  int tracked = 0;
  double worst = 0;
  EXPECT_EQ(lostOutsidePerturbation(Perturbation::Occluder, tracked, worst), 0);
  EXPECT_GE(tracked, 18);  // measured 20: lost on 5 of the 8 occluded frames, then re-acquired
  EXPECT_LT(worst, 1.0);
}

TEST_F(HomographyFrameTrackerTest, TracksThroughMotionBlur) {
  int tracked = 0;
  double worst = 0;
  lostOutsidePerturbation(Perturbation::Blur, tracked, worst);
  // Blur over the whole sequence: measured 18 of 25 registered (7 frames in the middle fall
  // just under the 35% inlier rule, then tracking re-acquires); the smeared corners cost
  // accuracy: measured 1.23 px worst at the frame corners.
  EXPECT_GE(tracked, 16);
  EXPECT_LT(worst, 1.5);
}
