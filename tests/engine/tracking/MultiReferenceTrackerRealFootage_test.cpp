// MultiReferenceTracker on real footage with true poses: the shared desk clip
// (../shared/data/desk-chessboard: 400 hand-held 752x480 frames of a desk with a chessboard, a
// wide-angle calibrated lens, per-frame poses from the board good to ~0.2 px). The map is
// prepared from frames 0 and 40 with their true poses, as `reftrack prepare --input frames
// --ref-frames 0,40 --poses groundtruth.txt` does, with the default parameters; the score is the
// dataset's: a 10 cm cube standing on the board at (0.16, -0.10, 0), its 8 vertices projected with
// K alone, mean pixel distance between the estimated and the true pose. Skipped (with a message)
// where ../shared/data is absent, e.g. in a fresh clone.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "TestPaths.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/TumTrajectory.hpp"
#include "engine/reference/MultiReferencePreparer.hpp"
#include "engine/tracking/MultiReferenceTracker.hpp"

namespace reftrack {
namespace {

struct DeskClip {
  PinholeCamera camera;
  std::vector<cv::Mat> frames;
  std::vector<RigidPose> truth;  // world -> camera, per frame
  MultiReferenceMap map;

  static std::optional<DeskClip> load() {
    const std::optional<std::filesystem::path> data = test::sharedDataDir();
    if (!data) return std::nullopt;
    const std::filesystem::path dir = *data / "desk-chessboard";
    if (!std::filesystem::exists(dir / "groundtruth.txt")) return std::nullopt;
    DeskClip clip;
    clip.camera = PinholeCamera::load(dir / "camera.yml");
    const TumTrajectory gt = TumTrajectory::load(dir / "groundtruth.txt");
    for (int i = 0; i < 400; ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "%06d.jpg", i);
      cv::Mat frame = cv::imread((dir / "frames" / name).string(), cv::IMREAD_GRAYSCALE);
      const std::optional<RigidPose> pose = gt.poseAt(i / 30.0, 1e-3);
      if (frame.empty() || !pose) return std::nullopt;
      clip.frames.push_back(frame);
      clip.truth.push_back(*pose);
    }
    clip.map = clip.mapFrom(0, 40);
    return clip;
  }

  // `reftrack prepare --ref-frames a,b --poses groundtruth.txt` with the default parameters.
  MultiReferenceMap mapFrom(int a, int b) const {
    const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
    const std::vector<ReferenceImage> refs = {{frames[ua], "frame " + std::to_string(a)},
                                              {frames[ub], "frame " + std::to_string(b)}};
    return MultiReferencePreparer(camera)
        .prepare(refs, {truth[ua], truth[ub]}, "groundtruth.txt")
        .map;
  }

  // The dataset's score: the cube's vertices through K alone (no lens), mean distance (pixels).
  double cubeError(int frame, const RigidPose& estimate) const {
    const Eigen::Vector3d centre(0.16, -0.10, 0.0);
    double sum = 0.0;
    for (int v = 0; v < 8; ++v) {
      const Eigen::Vector3d X = centre + Eigen::Vector3d((v & 1) ? 0.05 : -0.05,
                                                         (v & 2) ? 0.05 : -0.05, (v & 4) ? 0.1 : 0);
      sum += (camera.project(estimate * X) -
              camera.project(truth[static_cast<std::size_t>(frame)] * X))
                 .norm();
    }
    return sum / 8.0;
  }
};

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v.empty() ? NAN : v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

class MultiReferenceTrackerRealFootage : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (std::optional<DeskClip> c = DeskClip::load()) clip_ = new DeskClip(std::move(*c));
  }
  static void TearDownTestSuite() {
    delete clip_;
    clip_ = nullptr;
  }
  void SetUp() override {
    if (clip_ == nullptr)
      GTEST_SKIP() << "../shared/data/desk-chessboard not available (the shared real recordings)";
  }
  static DeskClip* clip_;
};
DeskClip* MultiReferenceTrackerRealFootage::clip_ = nullptr;

// The clip starts at reference 0: the paper's start near a reference gives the first frame its
// pose (before issue 24 the relocaliser took every frame and none was tracked). 0.5 px: the
// truth's own noise is ~0.2 px, and frame 0 is the reference itself.
TEST_F(MultiReferenceTrackerRealFootage, TheFirstFrameGetsAPose) {
  MultiReferenceTracker tracker(clip_->map, TrackerParams{});
  const MultiReferenceResult r = tracker.process(clip_->frames[0]);
  ASSERT_EQ(r.tracking.state, TrackingState::Tracking) << r.tracking.message;
  EXPECT_LT(clip_->cubeError(0, *r.tracking.worldToCamera), 0.5);
}

// The whole clip in order with the default parameters, against issue 24's bounds: >= 99.5% of the
// frames tracked from frame 0, cube error p95 <= 0.9 px and max below 1.5 px, mean <= 0.35 px.
// Measured (learned reliability on): mean 0.344, p95 0.769, max 1.20 px (0.367 / 0.807 / 1.33
// without it). The mean is held to 0.36: 0.01 of room for other CPUs' SIMD float paths.
TEST_F(MultiReferenceTrackerRealFootage, TracksTheWholeClipWithinTheBounds) {
  MultiReferenceTracker tracker(clip_->map, TrackerParams{});
  std::vector<double> errors;
  for (int i = 0; i < static_cast<int>(clip_->frames.size()); ++i) {
    const MultiReferenceResult r = tracker.process(clip_->frames[static_cast<std::size_t>(i)]);
    if (r.tracking.state == TrackingState::Tracking)
      errors.push_back(clip_->cubeError(i, *r.tracking.worldToCamera));
  }
  EXPECT_GE(static_cast<double>(errors.size()), 0.995 * static_cast<double>(clip_->frames.size()));
  double mean = 0.0;
  for (double e : errors) mean += e;
  mean /= static_cast<double>(errors.size());
  EXPECT_LE(mean, 0.36);
  EXPECT_LE(percentile(errors, 0.95), 0.9);
  RecordProperty("cube_error_mean_px", std::to_string(mean));
  EXPECT_LT(*std::max_element(errors.begin(), errors.end()), 1.5);
}

// The learned reliability (pose.reliability_prior_observations) over a long session: the clip
// played three times in a row (1200 frames; each replay jumps from frame 399 back to frame 0)
// keeps every frame tracked, and the later plays are no worse than the first (no weight running
// away to a few points). Measured: mean 0.344, 0.331, 0.330 px (five plays: 0.330 on).
TEST_F(MultiReferenceTrackerRealFootage, TheLearnedReliabilityStaysStableOverALongSession) {
  MultiReferenceTracker tracker(clip_->map, TrackerParams{});
  std::vector<double> means;
  for (int play = 0; play < 3; ++play) {
    double sum = 0.0;
    int tracked = 0;
    for (int i = 0; i < static_cast<int>(clip_->frames.size()); ++i) {
      const MultiReferenceResult r = tracker.process(clip_->frames[static_cast<std::size_t>(i)]);
      if (r.tracking.state != TrackingState::Tracking) continue;
      sum += clip_->cubeError(i, *r.tracking.worldToCamera);
      ++tracked;
    }
    EXPECT_GE(static_cast<double>(tracked), 0.995 * static_cast<double>(clip_->frames.size()))
        << "play " << play;
    means.push_back(sum / std::max(tracked, 1));
  }
  for (int play = 1; play < 3; ++play)
    EXPECT_LE(means[static_cast<std::size_t>(play)], means[0] + 0.005) << "play " << play;
  RecordProperty(
      "cube_error_mean_px_per_play",
      std::to_string(means[0]) + " " + std::to_string(means[1]) + " " + std::to_string(means[2]));
}

// Every 8th frame as a cold start (the tracker reset before each): no pose more than 5 px off,
// and nearly all frames posed (measured on all 400: 389 posed, all within 1.7 px; every 8th: 49
// of 50).
TEST_F(MultiReferenceTrackerRealFootage, ColdStartsGiveNoWrongPose) {
  MultiReferenceTracker tracker(clip_->map, TrackerParams{});
  int posed = 0, frames = 0;
  for (std::size_t i = 0; i < clip_->frames.size(); i += 8) {
    tracker.reset();
    ++frames;
    const MultiReferenceResult r = tracker.process(clip_->frames[i]);
    if (r.tracking.state != TrackingState::Tracking) continue;
    ++posed;
    EXPECT_LT(clip_->cubeError(static_cast<int>(i), *r.tracking.worldToCamera), 5.0)
        << "frame " << i << ": " << r.tracking.message;
  }
  EXPECT_GE(posed, frames * 9 / 10);
}

// References 200 and 240: cold starts near them on frames 330-338 once gave poses two chessboard
// squares off (93 px) that kept 13-18 matches to "distinctive" corners; the ratio-test keypoints
// (relocalisation.min_keypoint_support) refuse them. Each frame is either refused or right.
TEST_F(MultiReferenceTrackerRealFootage, StartsAPeriodOffOnTheChessboardAreRefused) {
  MultiReferenceTracker tracker(clip_->mapFrom(200, 240), TrackerParams{});
  int posed = 0;
  for (int i = 330; i <= 338; ++i) {
    tracker.reset();
    const MultiReferenceResult r = tracker.process(clip_->frames[static_cast<std::size_t>(i)]);
    if (r.tracking.state != TrackingState::Tracking) continue;
    ++posed;
    EXPECT_LT(clip_->cubeError(i, *r.tracking.worldToCamera), 5.0)
        << "frame " << i << ": " << r.tracking.message;
  }
  EXPECT_GE(posed, 1);  // not refused wholesale: the right starts get through (measured: all 9)
}

// Abrupt changes of view, played as one sequence without a reset (issue 32): the clip shuffled
// (every frame a jump) in two orders, and cut into 8 segments played in a shuffled order. Before
// every pose was checked (PoseVerifier), the shuffled clip gave 243 poses more than 5 px off and
// the cut clip 150 (3 cuts never re-acquired); with the check alone, 1 pose 5-9 px off per
// shuffled order (order 4: 9.1 px), which the match around the pose after a jump removed.
// Bounds: no pose more than 5 px off; shuffled >= 380 of 400 within 1.5 px (measured 388 and 393,
// every pose within 1.2 px); every cut re-acquired within 1 frame (measured: on its first frame).
TEST_F(MultiReferenceTrackerRealFootage, AbruptChangesOfViewGiveNoWrongPose) {
  std::vector<int> inOrder(400);
  std::iota(inOrder.begin(), inOrder.end(), 0);
  const auto shuffledWith = [&](std::uint64_t seed) {
    std::vector<int> order = inOrder;
    std::mt19937_64 rng(seed);
    std::shuffle(order.begin(), order.end(), rng);
    return order;
  };
  std::mt19937_64 rng(1);  // the segments' order: as drawn after the 400 frames' shuffle
  std::vector<int> discarded = inOrder;
  std::shuffle(discarded.begin(), discarded.end(), rng);
  std::vector<int> segments = {0, 1, 2, 3, 4, 5, 6, 7};
  std::shuffle(segments.begin(), segments.end(), rng);
  std::vector<int> cut;
  for (int s : segments)
    for (int k = 50 * s; k < 50 * s + 50; ++k) cut.push_back(k);
  const std::vector<std::pair<std::string, std::vector<int>>> orders = {
      {"shuffled (seed 1)", shuffledWith(1)}, {"shuffled (seed 4)", shuffledWith(4)}, {"cut", cut}};
  for (const auto& [name, order] : orders) {
    const bool isCut = name == "cut";
    MultiReferenceTracker tracker(clip_->map, TrackerParams{});
    int wrong = 0, good = 0, worstReacquire = 0, sinceCut = 0;
    bool reacquired = true;
    for (std::size_t i = 0; i < order.size(); ++i) {
      if (isCut && i % 50 == 0) {
        if (!reacquired) worstReacquire = 50;
        reacquired = false;
        sinceCut = 0;
      }
      const int k = order[i];
      const MultiReferenceResult r = tracker.process(clip_->frames[static_cast<std::size_t>(k)]);
      const double e =
          r.tracking.worldToCamera ? clip_->cubeError(k, *r.tracking.worldToCamera) : NAN;
      EXPECT_FALSE(e > 5.0) << name << " position " << i << ", frame " << k << ": " << e
                            << " px off (" << r.tracking.message << ")";
      wrong += e > 5.0 ? 1 : 0;
      good += e <= 1.5 ? 1 : 0;
      if (!reacquired && e <= 1.5) {
        reacquired = true;
        worstReacquire = std::max(worstReacquire, sinceCut);
      }
      ++sinceCut;
    }
    std::printf("%s: %d within 1.5 px, %d more than 5 px off, worst re-acquisition %d frames\n",
                name.c_str(), good, wrong, worstReacquire);
    EXPECT_EQ(wrong, 0);
    if (isCut) {
      EXPECT_LE(worstReacquire, 1);
    } else {
      EXPECT_GE(good, 380);
    }
  }
}

}  // namespace
}  // namespace reftrack
