// MultiReferenceTracker on real footage with true poses (skipped, with a message, where
// ../shared/data is absent, e.g. in a fresh clone):
// - the desk clip (../shared/data/desk-chessboard: 400 hand-held 752x480 frames of a desk with a
//   chessboard, a wide-angle calibrated lens, per-frame poses from the board good to ~0.2 px);
//   score: a 10 cm cube standing on the board at (0.16, -0.10, 0);
// - the shelf clip (../shared/data/shelf-apriltags: 210 undistorted 752x480 frames of a shelf
//   corner with AprilTag sheets, poses from 12 tag corners per frame, good to a few tenths of a
//   pixel); score: a 5 cm cube whose base is centred at (0.1, 0.2, -0.12).
// The map is prepared from two frames with their true poses, as `reftrack prepare --input frames
// --ref-frames a,b --poses groundtruth.txt` does, with the default parameters; the score is the
// cube's 8 vertices projected with K alone, mean pixel distance between the estimated and the
// true pose (as `bench-real --cube-centre --cube-edge` scores it).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <numeric>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <random>
#include <string>
#include <thread>
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

// A clip of ../shared/data with its true poses and the map of two of its frames.
struct RealClip {
  PinholeCamera camera;
  std::vector<cv::Mat> frames;
  std::vector<RigidPose> truth;  // world -> camera, per frame
  MultiReferenceMap map;
  Eigen::Vector3d cubeBase;  // centre of the scoring cube's base (world, m); it extends to +z
  double cubeEdge = 0.1;

  // `folder` of ../shared/data, its first `count` frames (NNNNNN.`extension` at index / 30 s), the
  // map of frames a and b; nullopt when absent. `colour`: the frames read in colour, as `reftrack`
  // reads them (the tracker converts them; a decoder's own grey differs by a grey level here and
  // there, enough to move a frame at the edge of the support limits).
  static std::optional<RealClip> load(const std::string& folder, int count, int a, int b,
                                      const Eigen::Vector3d& cubeBase, double cubeEdge,
                                      const std::string& extension = "jpg", bool colour = false) {
    const std::optional<std::filesystem::path> data = test::sharedDataDir();
    if (!data) return std::nullopt;
    const std::filesystem::path dir = *data / folder;
    if (!std::filesystem::exists(dir / "groundtruth.txt")) return std::nullopt;
    RealClip clip;
    clip.camera = PinholeCamera::load(dir / "camera.yml");
    const TumTrajectory gt = TumTrajectory::load(dir / "groundtruth.txt");
    for (int i = 0; i < count; ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "%06d.", i);
      cv::Mat frame = cv::imread((dir / "frames" / (name + extension)).string(),
                                 colour ? cv::IMREAD_COLOR : cv::IMREAD_GRAYSCALE);
      const std::optional<RigidPose> pose = gt.poseAt(i / 30.0, 1e-3);
      if (frame.empty() || !pose) return std::nullopt;
      clip.frames.push_back(frame);
      clip.truth.push_back(*pose);
    }
    clip.cubeBase = cubeBase;
    clip.cubeEdge = cubeEdge;
    clip.map = clip.mapFrom(a, b);
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
    const double h = 0.5 * cubeEdge;
    double sum = 0.0;
    for (int v = 0; v < 8; ++v) {
      const Eigen::Vector3d X =
          cubeBase + Eigen::Vector3d((v & 1) ? h : -h, (v & 2) ? h : -h, (v & 4) ? cubeEdge : 0);
      sum += (camera.project(estimate * X) -
              camera.project(truth[static_cast<std::size_t>(frame)] * X))
                 .norm();
    }
    return sum / 8.0;
  }
};

std::optional<RealClip> loadDesk() {
  return RealClip::load("desk-chessboard", 400, 0, 40, Eigen::Vector3d(0.16, -0.10, 0.0), 0.1);
}
std::optional<RealClip> loadShelf() {
  return RealClip::load("shelf-apriltags", 210, 0, 60, Eigen::Vector3d(0.1, 0.2, -0.12), 0.05);
}
std::optional<RealClip> loadVisp() {
  return RealClip::load("visp-desk-apriltags", 99, 0, 40, Eigen::Vector3d(0.18, 0.12, 0.0), 0.1,
                        "png", true);
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v.empty() ? NAN : v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

// The tests of one clip: loaded once for the suite, each test skipped (with a message) without it.
template <class Clip>
class RealClipSuite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (std::optional<RealClip> c = Clip::load()) clip_ = new RealClip(std::move(*c));
  }
  static void TearDownTestSuite() {
    delete clip_;
    clip_ = nullptr;
  }
  void SetUp() override {
    if (clip_ == nullptr)
      GTEST_SKIP() << "../shared/data/" << Clip::kFolder
                   << " not available (the shared real recordings)";
  }
  static inline RealClip* clip_ = nullptr;
};
struct Desk {
  static constexpr const char* kFolder = "desk-chessboard";
  static std::optional<RealClip> load() { return loadDesk(); }
};
struct Shelf {
  static constexpr const char* kFolder = "shelf-apriltags";
  static std::optional<RealClip> load() { return loadShelf(); }
};
struct Visp {
  static constexpr const char* kFolder = "visp-desk-apriltags";
  static std::optional<RealClip> load() { return loadVisp(); }
};
using MultiReferenceTrackerRealFootage = RealClipSuite<Desk>;

// The clip starts at reference 0: the paper's start near a reference gives the first frame its
// pose (before issue 24 the relocaliser took every frame and none was tracked). 0.5 px: the
// truth's own noise is ~0.2 px, and frame 0 is the reference itself.
TEST_F(MultiReferenceTrackerRealFootage, TheFirstFrameGetsAPose) {
  MultiReferenceTracker tracker(clip_->map, TrackerParams{});
  const MultiReferenceResult r = tracker.process(clip_->frames[0]);
  ASSERT_EQ(r.tracking.state, TrackingState::Tracking) << r.tracking.message;
  EXPECT_LT(clip_->cubeError(0, *r.tracking.worldToCamera), 0.5);
}

// The whole clip in order with the default parameters, against issue 24's bounds: every frame
// tracked from frame 0 (frames 174 and 389, unsure by the check of every pose and placed a few
// pixels elsewhere by the relocaliser's second opinion, were lost while that opinion was held to
// the PnP threshold), cube error p95 <= 0.9 px and max below 1.5 px, mean <= 0.35 px. Measured
// (learned reliability on): mean 0.344, p95 0.770, max 1.20 px (0.367 / 0.807 / 1.33 without
// it). The mean is held to 0.36: 0.01 of room for other CPUs' SIMD float paths.
TEST_F(MultiReferenceTrackerRealFootage, TracksTheWholeClipWithinTheBounds) {
  MultiReferenceTracker tracker(clip_->map, TrackerParams{});
  std::vector<double> errors;
  for (int i = 0; i < static_cast<int>(clip_->frames.size()); ++i) {
    const MultiReferenceResult r = tracker.process(clip_->frames[static_cast<std::size_t>(i)]);
    if (r.tracking.state == TrackingState::Tracking)
      errors.push_back(clip_->cubeError(i, *r.tracking.worldToCamera));
  }
  EXPECT_EQ(errors.size(), clip_->frames.size());
  double mean = 0.0;
  for (double e : errors) mean += e;
  mean /= static_cast<double>(errors.size());
  EXPECT_LE(mean, 0.36);
  EXPECT_LE(percentile(errors, 0.95), 0.9);
  RecordProperty("cube_error_mean_px", std::to_string(mean));
  EXPECT_LT(*std::max_element(errors.begin(), errors.end()), 1.5);
}

// The clip in order asks the relocaliser's second opinion on 28 unsure poses tracked on (the far
// views, frames 169-175 and 383-399, and five between 276 and 298), 43-60 ms each. With
// pose.verify_unsure_every_frames (15) an opinion that kept one stands for the next 14 frames of
// the unbroken track: no two asked within 15 tracked frames, under a third of them asked (5
// measured), and, as no opinion refused a pose tracked on in this clip, the very same poses.
TEST_F(MultiReferenceTrackerRealFootage, ASecondOpinionStandsForTheNextFramesOfTheTrack) {
  struct Play {
    std::vector<std::optional<RigidPose>> poses;
    std::vector<int> asked;  // frames whose pose was put to the relocaliser
  };
  const auto play = [&](int every) {
    TrackerParams params;
    params.pose.verifyUnsureEveryFrames = every;
    MultiReferenceTracker tracker(clip_->map, params);
    Play out;
    for (int i = 0; i < static_cast<int>(clip_->frames.size()); ++i) {
      const MultiReferenceResult r = tracker.process(clip_->frames[static_cast<std::size_t>(i)]);
      out.poses.push_back(r.tracking.worldToCamera);
      for (const auto& [stage, ms] : r.tracking.timings)
        if (stage == "confirm") {
          out.asked.push_back(i);
          break;
        }
    }
    return out;
  };
  const Play everyFrame = play(1);
  const Play standing = play(TrackerParams{}.pose.verifyUnsureEveryFrames);
  EXPECT_GE(everyFrame.asked.size(), 20u);
  EXPECT_LE(3 * standing.asked.size(), everyFrame.asked.size());
  for (std::size_t k = 1; k < standing.asked.size(); ++k)
    EXPECT_GE(standing.asked[k] - standing.asked[k - 1], 15) << "frame " << standing.asked[k];
  ASSERT_EQ(standing.poses.size(), everyFrame.poses.size());
  for (std::size_t i = 0; i < standing.poses.size(); ++i) {
    ASSERT_EQ(standing.poses[i].has_value(), everyFrame.poses[i].has_value()) << "frame " << i;
    if (standing.poses[i]) {
      EXPECT_LT((standing.poses[i]->toVector6() - everyFrame.poses[i]->toVector6()).norm(), 1e-9)
          << "frame " << i;
    }
  }
  RecordProperty("second_opinions", std::to_string(everyFrame.asked.size()) + " -> " +
                                        std::to_string(standing.asked.size()));
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

// Other threads busy on every core until destroyed: the machine's load, inside this process
// (whose CPU time a budget charged in measured time would count).
class CpuBurners {
 public:
  CpuBurners() {
    const unsigned n = std::max(2u, std::thread::hardware_concurrency());
    for (unsigned i = 0; i < n; ++i)
      threads_.emplace_back([this, i] {
        double x = 1.0 + i;
        while (!stop_.load(std::memory_order_relaxed))
          for (int k = 0; k < 10000; ++k) x = x * 1.0000001 + 1e-9;
        sink_.fetch_add(x > 0.0 ? 1 : 0);
      });
  }
  ~CpuBurners() {
    stop_ = true;
    for (std::thread& t : threads_) t.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::atomic<int> sink_{0};
  std::vector<std::thread> threads_;
};

// Recorded input gives the same poses on any machine load: 60 frames — 25 in order, 12 of an
// unrelated scene (a random texture: the recovery searches, then the budget holds it back), then
// a cut to frames 300-322, found again by the relocaliser — played twice, the second time with
// every core busy with other threads of this process. The states and the poses' bytes are equal.
// (With the budget charged in measured process CPU time, the burning threads emptied it and the
// second run searched fewer frames.)
TEST_F(MultiReferenceTrackerRealFootage, TheSameFramesGiveTheSameTrajectoryUnderLoad) {
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 25; ++i) frames.push_back(clip_->frames[static_cast<std::size_t>(i)]);
  cv::RNG rng(7);
  for (int i = 0; i < 12; ++i) {
    cv::Mat texture(clip_->frames[0].size(), CV_8UC1);
    rng.fill(texture, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(texture, texture, cv::Size(0, 0), 2.0);
    frames.push_back(texture);
  }
  for (int i = 300; i < 323; ++i) frames.push_back(clip_->frames[static_cast<std::size_t>(i)]);
  struct Run {
    std::string bytes;  // per frame: the state and the pose's 4x4 doubles, as stored
    int searched = 0, heldBack = 0, relocalised = 0;
  };
  const auto play = [&] {
    Run run;
    MultiReferenceTracker tracker(clip_->map, TrackerParams{});
    for (const cv::Mat& frame : frames) {
      const MultiReferenceResult r = tracker.process(frame);
      run.bytes += toString(r.tracking.state);
      if (r.tracking.worldToCamera) {
        const Eigen::Matrix4d T = r.tracking.worldToCamera->matrix4();
        run.bytes.append(reinterpret_cast<const char*>(T.data()), sizeof(double) * 16);
      }
      run.searched += r.recovery.ran ? 1 : 0;
      run.heldBack += r.tracking.message.find("budget") != std::string::npos ? 1 : 0;
      run.relocalised += r.relocalisation.succeeded ? 1 : 0;
    }
    return run;
  };
  const Run quiet = play();
  Run loaded;
  {
    const CpuBurners burners;
    loaded = play();
  }
  // The run is one that exercises the budget: searches, frames held back, a relocalisation.
  EXPECT_GE(quiet.searched, 3);
  EXPECT_GE(quiet.heldBack, 1);
  EXPECT_GE(quiet.relocalised, 1);
  EXPECT_EQ(loaded.searched, quiet.searched);
  EXPECT_EQ(loaded.heldBack, quiet.heldBack);
  EXPECT_TRUE(loaded.bytes == quiet.bytes) << "the trajectories differ under load";
  RecordProperty("searched_held_back_relocalised", std::to_string(quiet.searched) + " " +
                                                       std::to_string(quiet.heldBack) + " " +
                                                       std::to_string(quiet.relocalised));
}

// The scene coming back after a long look elsewhere: desk frames 0-24, 90 frames of an unrelated
// scene (random textures: every search fails and the budget settles to its rate), then frames
// 25-59. A frame that looks like the references (relocalisation.resemblance_min_score) may spend
// the reserve kept for it, so the first frame back is searched and tracked; without it the
// return waits for the budget (here 14 frames). Charged while away: within the burst and the
// rate per frame, as before.
TEST_F(MultiReferenceTrackerRealFootage, TheSceneComingBackIsSearchedAtOnce) {
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 25; ++i) frames.push_back(clip_->frames[static_cast<std::size_t>(i)]);
  cv::RNG rng(11);
  for (int i = 0; i < 90; ++i) {
    cv::Mat texture(clip_->frames[0].size(), CV_8UC1);
    rng.fill(texture, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(texture, texture, cv::Size(0, 0), 2.0);
    frames.push_back(texture);
  }
  const std::size_t back = frames.size();
  for (int i = 25; i < 60; ++i) frames.push_back(clip_->frames[static_cast<std::size_t>(i)]);
  const auto framesToReturn = [&](const TrackerParams& params, double& chargedAway) {
    MultiReferenceTracker tracker(clip_->map, params);
    int waited = -1;
    for (std::size_t k = 0; k < frames.size(); ++k) {
      const MultiReferenceResult r = tracker.process(frames[k]);
      if (k == back) chargedAway = tracker.recoveryChargedMs();
      if (k >= back && r.tracking.state == TrackingState::Tracking) {
        waited = static_cast<int>(k - back);
        const double px = clip_->cubeError(25 + waited, *r.tracking.worldToCamera);
        EXPECT_LT(px, 2.0) << "the first pose back, frame " << 25 + waited;
        break;
      }
      EXPECT_FALSE(k > 24 && k < back && r.tracking.state == TrackingState::Tracking)
          << "a pose on a random texture, frame " << k;
    }
    return waited;
  };
  double chargedWith = 0.0, chargedWithout = 0.0;
  const int with = framesToReturn(TrackerParams{}, chargedWith);
  TrackerParams off;
  off.relocalisation.resemblanceMinScore = 0.0;
  const int without = framesToReturn(off, chargedWithout);
  EXPECT_GE(with, 0);
  EXPECT_LE(with, 1);
  EXPECT_GT(without, with);  // the budget alone made it wait
  const TrackerParams defaults;
  const double bound = defaults.relocalisation.budgetBurstMs +
                       defaults.relocalisation.budgetMsPerFrame * 91 + 60.0;  // + one attempt
  EXPECT_LE(chargedWith, bound);
  RecordProperty("frames_to_return_with_without",
                 std::to_string(with) + " " + std::to_string(without));
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

// Orders of a clip's frames played as one sequence without a reset (abrupt changes of view): the
// frames shuffled (every frame a jump), or cut into 8 segments played in a shuffled order (as
// `bench-real --order shuffled-sequence,cuts:8` plays them; the segments' order here is the draw
// after the frames' shuffle).
struct AbruptOrder {
  std::string name;
  std::vector<int> frames;
  int segment = 0;  // > 0: cut into segments of this many frames
};
std::vector<AbruptOrder> abruptOrders(int count, const std::vector<std::uint64_t>& seeds) {
  std::vector<int> inOrder(static_cast<std::size_t>(count));
  std::iota(inOrder.begin(), inOrder.end(), 0);
  std::vector<AbruptOrder> orders;
  for (std::uint64_t seed : seeds) {
    std::vector<int> order = inOrder;
    std::mt19937_64 rng(seed);
    std::shuffle(order.begin(), order.end(), rng);
    orders.push_back({"shuffled (seed " + std::to_string(seed) + ")", order, 0});
  }
  std::mt19937_64 rng(1);  // the segments' order: as drawn after the frames' shuffle
  std::vector<int> discarded = inOrder;
  std::shuffle(discarded.begin(), discarded.end(), rng);
  std::vector<int> segments = {0, 1, 2, 3, 4, 5, 6, 7};
  std::shuffle(segments.begin(), segments.end(), rng);
  const int length = count / 8;
  AbruptOrder cut{"cut", {}, length};
  for (int s : segments)
    for (int k = length * s; k < length * s + length; ++k) cut.frames.push_back(k);
  orders.push_back(cut);
  return orders;
}

struct AbruptScore {
  int posed = 0, good = 0, wrong = 0;  // posed; within 1.5 px; more than 5 px off
  int worstReacquire = 0;              // frames after a cut until one within 1.5 px (cuts only)
  double maxError = 0.0;               // px, over the posed frames
};
AbruptScore playAbrupt(const RealClip& clip, const AbruptOrder& order) {
  MultiReferenceTracker tracker(clip.map, TrackerParams{});
  AbruptScore score;
  int sinceCut = 0;
  bool reacquired = true;
  for (std::size_t i = 0; i < order.frames.size(); ++i) {
    if (order.segment > 0 && i % static_cast<std::size_t>(order.segment) == 0) {
      if (!reacquired) score.worstReacquire = order.segment;
      reacquired = false;
      sinceCut = 0;
    }
    const int k = order.frames[i];
    const MultiReferenceResult r = tracker.process(clip.frames[static_cast<std::size_t>(k)]);
    if (!r.tracking.worldToCamera) {
      ++sinceCut;
      continue;
    }
    const double e = clip.cubeError(k, *r.tracking.worldToCamera);
    EXPECT_FALSE(e > 5.0) << order.name << " position " << i << ", frame " << k << ": " << e
                          << " px off (" << r.tracking.message << ")";
    ++score.posed;
    score.wrong += e > 5.0 ? 1 : 0;
    score.good += e <= 1.5 ? 1 : 0;
    score.maxError = std::max(score.maxError, e);
    if (!reacquired && e <= 1.5) {
      reacquired = true;
      score.worstReacquire = std::max(score.worstReacquire, sinceCut);
    }
    ++sinceCut;
  }
  if (!reacquired) score.worstReacquire = order.segment;
  std::printf(
      "%s: %d posed, %d within 1.5 px, %d more than 5 px off, max %.2f px, worst "
      "re-acquisition %d frames\n",
      order.name.c_str(), score.posed, score.good, score.wrong, score.maxError,
      score.worstReacquire);
  return score;
}

// The desk's abrupt changes of view (issue 32), in two shuffled orders and cut in 8. Before every
// pose was checked (PoseVerifier), the shuffled clip gave 243 poses more than 5 px off and the
// cut clip 150 (3 cuts never re-acquired); with the check alone, 1 pose 5-9 px off in most
// shuffled orders (seed 4: 9.1 px), which the match around the pose after a jump removed.
// Bounds: no pose more than 5 px off; shuffled >= 380 of 400 within 1.5 px (measured 388 and 393,
// every pose within 1.2 px); every cut re-acquired within 1 frame (measured: on its first frame).
TEST_F(MultiReferenceTrackerRealFootage, AbruptChangesOfViewGiveNoWrongPose) {
  for (const AbruptOrder& order : abruptOrders(400, {1, 4})) {
    const AbruptScore score = playAbrupt(*clip_, order);
    EXPECT_EQ(score.wrong, 0) << order.name;
    if (order.segment > 0) {
      EXPECT_LE(score.worstReacquire, 1);
    } else {
      EXPECT_GE(score.good, 380) << order.name;
    }
  }
}

// The shelf clip (references 0 and 60), as the desk's above: a scene of little texture besides
// printed tags, three planes seen at changing angles, a 5 cm cube.
using MultiReferenceTrackerShelf = RealClipSuite<Shelf>;

// In order with the default parameters: every frame tracked; measured mean 0.182, p95 0.353, max
// 0.56 px (per-frame SIFT+PnP 0.185, AKAZE 0.181 from the same references). Bounds: all 210
// frames; mean <= 0.19 px (0.01 of room for other CPUs' float paths, as the desk's), p95 <= 0.4,
// max < 0.8 px (the truth itself is good to a few tenths of a pixel).
TEST_F(MultiReferenceTrackerShelf, TracksTheWholeClipWithinTheBounds) {
  MultiReferenceTracker tracker(clip_->map, TrackerParams{});
  std::vector<double> errors;
  for (int i = 0; i < static_cast<int>(clip_->frames.size()); ++i) {
    const MultiReferenceResult r = tracker.process(clip_->frames[static_cast<std::size_t>(i)]);
    ASSERT_TRUE(r.tracking.worldToCamera.has_value())
        << "frame " << i << ": " << r.tracking.message;
    errors.push_back(clip_->cubeError(i, *r.tracking.worldToCamera));
  }
  const double mean =
      std::accumulate(errors.begin(), errors.end(), 0.0) / static_cast<double>(errors.size());
  EXPECT_LE(mean, 0.19);
  EXPECT_LE(percentile(errors, 0.95), 0.4);
  EXPECT_LT(*std::max_element(errors.begin(), errors.end()), 0.8);
  RecordProperty("cube_error_mean_px", std::to_string(mean));
}

// Shuffled (two orders) and cut in 8, one sequence each: measured every frame posed, all within
// 0.6 px, every cut on its first frame. Bounds: no pose more than 5 px off, >= 205 of 210 posed
// within 1.5 px, every cut re-acquired within 1 frame.
TEST_F(MultiReferenceTrackerShelf, AbruptChangesOfViewGiveNoWrongPose) {
  for (const AbruptOrder& order : abruptOrders(210, {1, 3})) {
    const AbruptScore score = playAbrupt(*clip_, order);
    EXPECT_EQ(score.wrong, 0) << order.name;
    EXPECT_GE(score.good, 205) << order.name;
    if (order.segment > 0) {
      EXPECT_LE(score.worstReacquire, 1);
    }
  }
}

// ViSP's desk clip (references 0 and 40; another camera than the desk's and the shelf's, a
// rolling shutter, repeated texture): in order with the default parameters. The keypoint layer's
// terms (wide_baseline.keypoint_points), with the support judged on the corners' terms, took it
// from 98 / 99 posed, mean 0.467, p95 1.41 px, true / predicted 1.67 to 99 / 99, 0.384, 0.92,
// 1.01 (per-frame AKAZE+PnP 0.371, SIFT+PnP 0.373 from the same references). Bounds: >= 98 frames
// posed, mean <= 0.42 px (between the two: the corners alone fail it), p95 <= 1.0, no pose more
// than 5 px off, and the median of true / predicted error within 0.7-1.4 (issue 41).
using MultiReferenceTrackerVisp = RealClipSuite<Visp>;

TEST_F(MultiReferenceTrackerVisp, TracksTheClipAsWellAsThePerFramePeers) {
  MultiReferenceTracker tracker(clip_->map, TrackerParams{});
  std::vector<Eigen::Vector3d> cube;  // the scored cube, whose error the prediction is for
  const double h = 0.5 * clip_->cubeEdge;
  for (int v = 0; v < 8; ++v)
    cube.push_back(clip_->cubeBase +
                   Eigen::Vector3d((v & 1) ? h : -h, (v & 2) ? h : -h, (v & 4) ? 2 * h : 0));
  tracker.setOverlayPoints(cube);
  std::vector<double> errors, ratios;
  for (int i = 0; i < static_cast<int>(clip_->frames.size()); ++i) {
    const MultiReferenceResult r = tracker.process(clip_->frames[static_cast<std::size_t>(i)]);
    if (!r.tracking.worldToCamera) {
      std::printf("frame %d: %s\n", i, r.tracking.message.c_str());
      continue;
    }
    errors.push_back(clip_->cubeError(i, *r.tracking.worldToCamera));
    if (r.predictedErrorPx && *r.predictedErrorPx > 0)
      ratios.push_back(errors.back() / *r.predictedErrorPx);
  }
  ASSERT_GE(errors.size(), 98U);
  const double mean =
      std::accumulate(errors.begin(), errors.end(), 0.0) / static_cast<double>(errors.size());
  EXPECT_LE(mean, 0.42);
  EXPECT_LE(percentile(errors, 0.95), 1.0);
  EXPECT_LT(*std::max_element(errors.begin(), errors.end()), 5.0);
  ASSERT_GE(ratios.size(), 90U);
  EXPECT_GE(percentile(ratios, 0.5), 0.7);
  EXPECT_LE(percentile(ratios, 0.5), 1.4);
  RecordProperty("cube_error_mean_px", std::to_string(mean));
  RecordProperty("true_over_predicted_median", std::to_string(percentile(ratios, 0.5)));
}

// A map of soft Kinect frames made from denser corners (references 440 and 460 of
// ../shared/data/kinect-kitchen, 19 cm and 10 degrees apart: their own corners give 43 points,
// the denser ones 233) is tracked with frames detected as densely. Before, the tracker's corners
// held 11-14 of the map's points and not one of frames 440-452 got a pose, the reference frame
// itself included ("too few 3D-2D matches"). Score: a cube of 8 cm edge centred 1 m in front of
// reference 440's camera, as bench-real's Kinect segments score it. Measured: all 13 frames
// posed; 0.8-3.1 px but frames 447-451 (11.4, 24.4, 22.8, 14.5, 5.7 px), where SIFT+PnP from the
// same references with the same truth is as far off (9.8, 25.8, 21.9, 16.7, 9.4 px: `bench-real`
// on frames 420-499, app/research/README.md): the given poses disagree with the images there
// (prepare's probe: 3.7 degrees). Bounds: every frame posed, median below 5 px, none beyond 30.
TEST(MultiReferenceTrackerKinect, AMapFromDenserCornersIsTrackedFromItsReferenceOn) {
  const std::optional<std::filesystem::path> data = test::sharedDataDir();
  if (!data || !std::filesystem::exists(*data / "kinect-kitchen" / "groundtruth.txt"))
    GTEST_SKIP() << "../shared/data/kinect-kitchen not available (the shared real recordings)";
  const std::filesystem::path dir = *data / "kinect-kitchen";
  const PinholeCamera camera = PinholeCamera::load(dir / "camera.yml");
  const TumTrajectory gt = TumTrajectory::load(dir / "groundtruth.txt");
  const auto frame = [&](int k) {
    char name[32];
    std::snprintf(name, sizeof name, "%06d.jpg", k);
    return cv::imread((dir / "frames" / name).string(), cv::IMREAD_GRAYSCALE);
  };
  const auto truth = [&](int k) { return gt.poseAt(k / 30.0, 1e-3).value(); };
  const MultiReferenceMap map = MultiReferencePreparer(camera)
                                    .prepare({{frame(440), "frame 440"}, {frame(460), "frame 460"}},
                                             {truth(440), truth(460)}, "groundtruth.txt")
                                    .map;
  ASSERT_TRUE(map.denserCorners.has_value());
  std::vector<Eigen::Vector3d> cube;
  for (int v = 0; v < 8; ++v)
    cube.push_back(truth(440).inverse() * Eigen::Vector3d((v & 1) ? 0.04 : -0.04,
                                                          (v & 2) ? 0.04 : -0.04,
                                                          (v & 4) ? 1.04 : 0.96));
  MultiReferenceTracker tracker(map, TrackerParams{});
  std::vector<double> errors;
  for (int k = 440; k <= 452; ++k) {
    const MultiReferenceResult r = tracker.process(frame(k));
    ASSERT_TRUE(r.tracking.worldToCamera.has_value())
        << "frame " << k << ": " << r.tracking.message;
    double sum = 0.0;
    for (const Eigen::Vector3d& X : cube)
      sum += (camera.project(*r.tracking.worldToCamera * X) - camera.project(truth(k) * X)).norm();
    errors.push_back(sum / 8.0);
    std::printf("frame %d: %.2f px\n", k, errors.back());
  }
  EXPECT_LT(percentile(errors, 0.5), 5.0);
  EXPECT_LT(*std::max_element(errors.begin(), errors.end()), 30.0);
  RecordProperty("cube_error_median_px", std::to_string(percentile(errors, 0.5)));
}

}  // namespace
}  // namespace reftrack
