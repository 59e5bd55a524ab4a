// PoseTracker on real footage: ViSP's hand-held postcard video (../shared/data/planar-videos,
// 161 frames, 640x480, no ground truth, K guessed by ViSP as fx = fy = 840 at the centre).
// The postcard plays the printed marker: its four corners fix the world frame. They are
// hand-clicked once on frame 0, refined there by cornerSubPix and carried through the video by the
// homography tracker (the scene is planar, so a homography maps them exactly); a solvePnP on them
// gives the "marker" pose of each frame (PostcardCardPoses.hpp). Two frames with those poses
// become V_A and V_B; the 6-DOF tracker then runs over the whole video, and each of its poses is
// checked against the card's corners in that frame, which the tracker never sees.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <opencv2/core.hpp>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "engine/config/TrackerParams.hpp"
#include "engine/reference/ReferencePoseRefiner.hpp"
#include "engine/reference/ReferencePreparer.hpp"
#include "engine/relocalisation/PostcardCardPoses.hpp"
#include "engine/relocalisation/Relocaliser.hpp"
#include "engine/tracking/MultiReferenceTracker.hpp"
#include "engine/tracking/PoseTracker.hpp"

namespace reftrack {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::min<double>(v.size() - 1, p * (v.size() - 1) + 0.5))];
}

class PoseTrackerRealFootage : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (auto clip = test::PostcardCardPoses::load())
      clip_ = new test::PostcardCardPoses(std::move(*clip));
  }
  static void TearDownTestSuite() {
    delete clip_;
    clip_ = nullptr;
  }
  void SetUp() override {
    if (clip_ == nullptr)
      GTEST_SKIP() << "../shared/data/planar-videos/video-postcard.mp4 not available";
  }
  static test::PostcardCardPoses* clip_;
};
test::PostcardCardPoses* PoseTrackerRealFootage::clip_ = nullptr;

// The clip's corners and card poses (steps 1-2, PostcardCardPoses) and the two-reference map from
// frames 0 and 100, shared by the tests.
struct PostcardReferences {
  PinholeCamera camera;
  std::vector<cv::Point3f> card;
  std::vector<std::optional<std::array<cv::Point2f, 4>>> corners;
  ReferenceMap map;
  long followed = 0;
  double aspectRatio = 0.0, aspectRms = 0.0;
};

PostcardReferences prepareReferences(const test::PostcardCardPoses& clip,
                                     const ReferencePreparerParams& params = {}) {
  PostcardReferences result;
  result.camera = clip.camera;
  result.card = clip.card;
  result.corners = clip.corners;
  result.followed = std::count_if(clip.corners.begin(), clip.corners.end(),
                                  [](const auto& c) { return c.has_value(); });
  result.aspectRatio = clip.aspectRatio;
  result.aspectRms = clip.aspectRms;
  // 3. References: frame 0 (V_A) and frame 100 (V_B, 3.4 cm away), poses from the postcard.
  const std::size_t a = 0, b = 100;
  if (!clip.poses[a] || !clip.poses[b]) return result;  // checked by the caller (no map)
  // Default parameters unless given (measured: a map of 44 points on this low-texture scene).
  const Preparation prep =
      ReferencePreparer(clip.camera, params)
          .prepare({clip.frames[a], "frame " + std::to_string(a)},
                   {clip.frames[b], "frame " + std::to_string(b)}, *clip.poses[a], *clip.poses[b],
                   "postcard corners (solvePnP)");
  result.map = prep.map;
  return result;
}

// Mean distance (pixels) between the card's corners projected with `worldToCamera` and those
// measured in the frame.
double cornerErrorPx(const PostcardReferences& refs, const RigidPose& worldToCamera,
                     const std::array<cv::Point2f, 4>& measured) {
  double sum = 0;
  for (int i = 0; i < 4; ++i) {
    const cv::Point3f& X = refs.card[static_cast<std::size_t>(i)];
    const Eigen::Vector2d p = refs.camera.project(worldToCamera, Eigen::Vector3d(X.x, X.y, X.z));
    sum += std::hypot(p.x() - measured[static_cast<std::size_t>(i)].x,
                      p.y() - measured[static_cast<std::size_t>(i)].y);
  }
  return sum / 4.0;
}

TEST_F(PoseTrackerRealFootage, PosesAgreeWithThePostcardCornersOnEveryFrame) {
  const test::PostcardCardPoses& f = *clip_;
  ASSERT_EQ(f.frames.size(), 161u);
  const PostcardReferences refs = prepareReferences(f);
  // Measured: the homography tracker registers every frame of this clip.
  ASSERT_GE(refs.followed, 155)
      << "the homography tracker lost too many frames of the postcard clip";
  RecordProperty("postcard_aspect_ratio", std::to_string(refs.aspectRatio));
  RecordProperty("postcard_pnp_rms_px", std::to_string(refs.aspectRms));
  // The guessed K and the card's corner rounding limit how well a rectangle fits.
  EXPECT_LT(refs.aspectRms, 1.5) << "no rectangle fits the followed postcard corners";
  ASSERT_FALSE(refs.map.matches.empty()) << "no postcard corners in frame 0 or 100";
  RecordProperty("reference_matches", std::to_string(refs.map.matches.size()));
  const double bestRatio = refs.aspectRatio, bestRms = refs.aspectRms;

  // 4. Track the whole clip; compare each pose with the corners measured in that frame.
  PoseTracker tracker(refs.map, TrackerParams{});
  std::vector<double> errors;
  int tracked = 0;
  for (std::size_t k = 0; k < f.frames.size(); ++k) {
    const PoseTrackingResult r = tracker.process(f.frames[k]);
    if (r.state != TrackingState::Tracking || !r.worldToCamera) continue;
    ++tracked;
    if (refs.corners[k]) errors.push_back(cornerErrorPx(refs, *r.worldToCamera, *refs.corners[k]));
  }
  const double trackedFraction = static_cast<double>(tracked) / f.frames.size();
  RecordProperty("tracked_fraction", std::to_string(trackedFraction));
  RecordProperty("corner_error_median_px", std::to_string(median(errors)));
  RecordProperty("corner_error_p95_px", std::to_string(percentile(errors, 0.95)));
  std::printf(
      "postcard clip: aspect %.3f (PnP RMS %.2f px), %zu reference matches, tracked %d/%zu, "
      "corner error median %.2f px, p95 %.2f px, max %.2f px\n",
      bestRatio, bestRms, refs.map.matches.size(), tracked, f.frames.size(), median(errors),
      percentile(errors, 0.95), percentile(errors, 1.0));
  // Measured: 161 of 161 frames tracked from a map of 43 points; every reported pose agrees
  // with corners the tracker never saw to 0.73 px median, 1.47 px worst. The card corners
  // themselves fit a rectangle only to ~0.7 px (the fit's RMS, with a guessed K), so the bounds
  // allow about twice that.
  EXPECT_GE(trackedFraction, 0.95);
  EXPECT_LT(median(errors), 1.5);
  EXPECT_LT(percentile(errors, 1.0), 2.5);
}

// The same clip through the MultiReferenceTracker, over the map as a version-2 map of two
// references with its keypoint layer: (a) the whole clip from frame 0, as above; (b) starts from
// frames spread over the clip, in shuffled order, each with a fresh tracker: the first frame is
// relocalised and verified, and the pose agrees with the card corners as the tracked poses do.
// Measured: 161 of 161 frames, 0.73 px median and 1.47 px worst (as the PoseTracker alone); 8 of
// 8 starts on their first frame, all relocalised, 1.36 px worst. The bounds are those of the test
// above.
TEST_F(PoseTrackerRealFootage, MultiReferenceTrackerTracksTheClipAndStartsMidClip) {
  const test::PostcardCardPoses& f = *clip_;
  ASSERT_EQ(f.frames.size(), 161u);
  const PostcardReferences refs = prepareReferences(f);
  ASSERT_FALSE(refs.map.matches.empty()) << "no postcard corners in frame 0 or 100";
  MultiReferenceMap map = MultiReferenceMap::fromPair(refs.map);
  buildReferenceKeypoints(map, RelocalisationParams{});

  MultiReferenceTracker tracker(map, TrackerParams{});
  std::vector<double> errors;
  int tracked = 0;
  for (std::size_t k = 0; k < f.frames.size(); ++k) {
    const MultiReferenceResult r = tracker.process(f.frames[k]);
    if (r.tracking.state != TrackingState::Tracking || !r.tracking.worldToCamera) continue;
    ++tracked;
    if (refs.corners[k])
      errors.push_back(cornerErrorPx(refs, *r.tracking.worldToCamera, *refs.corners[k]));
  }
  const double trackedFraction = static_cast<double>(tracked) / f.frames.size();
  std::printf(
      "postcard clip, multi-reference tracker: tracked %d/%zu, corner error median %.2f px, max "
      "%.2f px\n",
      tracked, f.frames.size(), median(errors), percentile(errors, 1.0));
  EXPECT_GE(trackedFraction, 0.95);
  EXPECT_LT(median(errors), 1.5);
  EXPECT_LT(percentile(errors, 1.0), 2.5);

  const std::vector<std::size_t> starts = {130, 25, 75, 150, 50, 110, 10, 90};
  int started = 0, relocalised = 0;
  std::vector<double> startErrors, relocalisationMs;
  for (const std::size_t s : starts) {
    MultiReferenceTracker fresh(map, TrackerParams{});
    const MultiReferenceResult r = fresh.process(f.frames[s]);
    if (r.relocalisation.attempted) relocalisationMs.push_back(r.relocalisation.ms);
    std::printf("start at frame %zu: %s (%s)\n", s, toString(r.tracking.state),
                r.tracking.state == TrackingState::Tracking ? r.tracking.message.c_str()
                                                            : r.relocalisation.message.c_str());
    if (r.tracking.state != TrackingState::Tracking || !r.tracking.worldToCamera) continue;
    ++started;
    relocalised += r.relocalisation.succeeded ? 1 : 0;
    if (refs.corners[s])
      startErrors.push_back(cornerErrorPx(refs, *r.tracking.worldToCamera, *refs.corners[s]));
  }
  std::printf(
      "mid-clip starts: %d of %zu on their first frame (%d relocalised), corner error max %.2f px, "
      "relocalisation median %.1f ms\n",
      started, starts.size(), relocalised, percentile(startErrors, 1.0), median(relocalisationMs));
  RecordProperty("mid_clip_starts",
                 std::to_string(started) + " of " + std::to_string(starts.size()));
  EXPECT_EQ(started, static_cast<int>(starts.size()));
  EXPECT_LT(percentile(startErrors, 1.0), 2.5);
}

// Real-footage diagnosis (issue 14 item 3): references 3.4 cm apart (frames 0 and 100), their
// poses from the card corners (a fiducial good to a fraction of a pixel), the camera wandering
// up to ~8 cm from both. The ground truth here is denser than the four card corners: a 7x7 grid
// on the card, placed by frame 0's card pose and carried to every frame by the homography
// tracker's H (cold and in-order registrations of this clip agree to 0.02-0.4 px), so the error
// is what content on the card would show. The map is tracked with reference B's pose as the
// card gives it, refined by ReferencePoseRefiner on the corners (what a format-2 map without
// peaks gives) and on the correlation peaks the points were triangulated from (format 3, the
// default preparation); each run prints its reasons for frames without a pose, tracked %, error
// mean / p95 and the mean error by distance from the nearest reference, and each map how far
// its points lie from the card's plane (the scene is a card on a table: the map's depth error).
TEST_F(PoseTrackerRealFootage, ErrorAwayFromTheReferencesWithRefinedReferencePoses) {
  const test::PostcardCardPoses& f = *clip_;
  ReferencePreparerParams givenPoses;
  givenPoses.refinePoses = false;
  const PostcardReferences refs = prepareReferences(f, givenPoses);
  ASSERT_FALSE(refs.map.matches.empty()) << "no postcard corners in frame 0 or 100";
  ASSERT_TRUE(refs.corners[0].has_value());
  const auto refined = [&](bool atPeaks, ReferencePoseRefinement& report) {
    MultiReferenceMap multi = MultiReferenceMap::fromPair(refs.map);
    if (!atPeaks)
      for (MapPoint& p : multi.points)
        for (PointObservation& o : p.observations) o.peak.reset();
    report = refineReferencePoses(multi);
    return multi.pair(0, 1);
  };
  ReferencePoseRefinement onCorners, onPeaks;
  const ReferenceMap cornersMap = refined(false, onCorners), peaksMap = refined(true, onPeaks);
  for (const auto& [name, r] : {std::pair{"corners", &onCorners}, std::pair{"peaks", &onPeaks}})
    std::printf(
        "reference B refined on the %s: moved %.2f mm, %.3f deg; reprojection RMS %.3f -> %.3f px "
        "over %d observations\n",
        name, r->movedMillimetres[1], r->movedDeg[1], r->initialRmsPx, r->finalRmsPx,
        r->observations);
  // The same preparation with preparation.refine_given_poses is the peaks-refined map; by
  // default given poses are kept as they are (issue 24: refining them raised the error on every
  // real clip with accurate poses).
  ReferencePreparerParams refineGiven;
  refineGiven.refineGivenPoses = true;
  const PostcardReferences refinedByOption = prepareReferences(f, refineGiven);
  ASSERT_EQ(refinedByOption.map.matches.size(), peaksMap.matches.size());
  EXPECT_LT(RigidPose::rotationDistance(refinedByOption.map.T_B, peaksMap.T_B), 1e-9);
  const PostcardReferences byDefault = prepareReferences(f);
  EXPECT_LT(RigidPose::rotationDistance(byDefault.map.T_B, refs.map.T_B), 1e-12);

  ASSERT_TRUE(f.poses[0].has_value());
  const RigidPose T0 = *f.poses[0];
  const double w = refs.card[1].x, h = refs.card[3].y;
  std::vector<Eigen::Vector3d> grid;
  std::vector<cv::Point2f> grid0;
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j) {
      grid.emplace_back(w * i / 6.0, h * j / 6.0, 0.0);
      const Eigen::Vector2d p = refs.camera.project(T0, grid.back());
      grid0.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
    }
  // Camera centres from the card corners (for the distance to the references only).
  std::vector<std::optional<Eigen::Vector3d>> centres(f.frames.size());
  for (std::size_t k = 0; k < f.frames.size(); ++k)
    if (f.poses[k]) centres[k] = f.poses[k]->cameraCentre();
  const Eigen::Vector3d cA = refs.map.T_A.cameraCentre(), cB = refs.map.T_B.cameraCentre();

  struct Run {
    int tracked = 0;
    std::vector<double> errors;
    std::map<std::string, int> reasons;
    std::array<std::vector<double>, 4> byDistance;  // < 2, 2-4, 4-6, >= 6 cm
  };
  auto run = [&](const ReferenceMap& map) {
    PoseTracker tracker(map, TrackerParams{});
    Run out;
    for (std::size_t k = 0; k < f.frames.size(); ++k) {
      const PoseTrackingResult r = tracker.process(f.frames[k]);
      if (r.state != TrackingState::Tracking || !r.worldToCamera) {
        out.reasons[r.message.substr(0, r.message.find(" ("))]++;
        continue;
      }
      ++out.tracked;
      if (!f.homographies[k] || !centres[k]) continue;
      std::vector<cv::Point2f> truth;
      cv::perspectiveTransform(grid0, truth, cv::Mat(*f.homographies[k]));
      double sum = 0;
      for (std::size_t i = 0; i < grid.size(); ++i) {
        const Eigen::Vector2d p = refs.camera.project(*r.worldToCamera, grid[i]);
        sum += std::hypot(p.x() - truth[i].x, p.y() - truth[i].y);
      }
      const double e = sum / static_cast<double>(grid.size());
      out.errors.push_back(e);
      const double d = std::min((*centres[k] - cA).norm(), (*centres[k] - cB).norm());
      out.byDistance[std::min<std::size_t>(3, static_cast<std::size_t>(d / 0.02))].push_back(e);
    }
    return out;
  };
  auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? std::nan("") : s / static_cast<double>(v.size());
  };
  // The map's points against the card's plane (world z = 0; the card lies on the table):
  // distance median and p90 (mm), and the plane fitted to them (z = a x + b y + c, least squares
  // over the points within 2 cm of it): its tilt (deg) and height at the origin (mm). Noise
  // scatters the points; a wrong relative pose of the references tilts and shifts them all.
  struct PlaneFit {
    double medianMm, p90Mm, tiltDeg, offsetMm;
  };
  auto planeFit = [](const ReferenceMap& map) {
    std::vector<double> d;
    std::vector<Eigen::Vector3d> near;
    const RigidPose AtoWorld = map.T_A.inverse();
    for (const ReferenceMatch& m : map.matches) {
      const Eigen::Vector3d X = AtoWorld * m.pointA;
      d.push_back(1000.0 * std::abs(X.z()));
      if (std::abs(X.z()) < 0.02) near.push_back(X);
    }
    Eigen::MatrixXd A(static_cast<Eigen::Index>(near.size()), 3);
    Eigen::VectorXd z(static_cast<Eigen::Index>(near.size()));
    for (std::size_t i = 0; i < near.size(); ++i) {
      A.row(static_cast<Eigen::Index>(i)) << near[i].x(), near[i].y(), 1.0;
      z(static_cast<Eigen::Index>(i)) = near[i].z();
    }
    const Eigen::Vector3d abc = A.colPivHouseholderQr().solve(z);
    return PlaneFit{median(d), percentile(d, 0.9),
                    std::atan(abc.head<2>().norm()) * 180.0 / 3.14159265358979323846,
                    1000.0 * abc.z()};
  };
  const Run given = run(refs.map), corners = run(cornersMap), peaks = run(peaksMap);
  for (const auto& [name, r, map] : {std::tuple{"card poses", &given, &refs.map},
                                     std::tuple{"refined on the corners", &corners, &cornersMap},
                                     std::tuple{"refined on the peaks", &peaks, &peaksMap}}) {
    const PlaneFit plane = planeFit(*map);
    std::printf(
        "postcard, %s: tracked %d/%zu, grid error mean %.3f px, p95 %.3f px, max %.3f px; mean by "
        "distance from the nearest reference <2 cm %.3f (%zu), 2-4 cm %.3f (%zu), 4-6 cm %.3f "
        "(%zu), >=6 cm %.3f (%zu); points off the card's plane: median %.2f mm, p90 %.2f mm, "
        "fitted "
        "plane tilted %.3f deg, %.2f mm at the origin\n",
        name, r->tracked, f.frames.size(), mean(r->errors), percentile(r->errors, 0.95),
        percentile(r->errors, 1.0), mean(r->byDistance[0]), r->byDistance[0].size(),
        mean(r->byDistance[1]), r->byDistance[1].size(), mean(r->byDistance[2]),
        r->byDistance[2].size(), mean(r->byDistance[3]), r->byDistance[3].size(), plane.medianMm,
        plane.p90Mm, plane.tiltDeg, plane.offsetMm);
    for (const auto& [reason, count] : r->reasons)
      std::printf("  no pose: %d x %s\n", count, reason.c_str());
  }
  RecordProperty("grid_error_mean_px", std::to_string(mean(peaks.errors)));
  RecordProperty("grid_error_p95_px", std::to_string(percentile(peaks.errors, 0.95)));
  // Measured: see the bounds.
  EXPECT_EQ(peaks.tracked, static_cast<int>(f.frames.size()));
  EXPECT_TRUE(peaks.reasons.empty());
  EXPECT_LT(mean(peaks.errors), mean(given.errors));
  EXPECT_LT(mean(peaks.errors), 0.8);
  EXPECT_LT(percentile(peaks.errors, 0.95), 1.9);
  EXPECT_LT(onPeaks.movedDeg[1], 0.2);
}

}  // namespace
}  // namespace reftrack
