#include "app/research/sixdof/RealFootageBenchmark.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>
#include <set>
#include <tuple>

#include "app/research/baselines/OrbPnpKalmanTracker.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"
#include "engine/core/ThreadCpuClock.hpp"
#include "engine/evaluation/PlanarTargetTruth.hpp"
#include "engine/evaluation/TrajectoryEvaluator.hpp"
#include "engine/reference/MultiReferencePreparer.hpp"
#include "engine/tracking/MultiReferenceTracker.hpp"

namespace reftrack::app {

RealFootageOptions RealFootageOptions::postcard(std::filesystem::path clip) {
  RealFootageOptions o;
  o.clip = std::move(clip);
  // Frame 0 of video-postcard.mp4, clicked by eye (refined by cornerSubPix).
  o.targetCorners = {cv::Point2f(64, 115), cv::Point2f(255, 83), cv::Point2f(312, 285),
                     cv::Point2f(69, 329)};
  return o;
}

void RealFootageOptions::check() const {
  if (frames < 0) throw Error("bench-real: --frames must be >= 0 (0: the whole clip)");
  if (references.size() < 2) throw Error("bench-real: --references needs at least two frames");
  std::set<int> seen;
  for (int r : references) {
    if (r < 0) throw Error("bench-real: --references: frame " + std::to_string(r) + " is < 0");
    if (!seen.insert(r).second)
      throw Error("bench-real: --references: frame " + std::to_string(r) + " given twice");
  }
  if (!(targetTopEdgeMetres > 0) || !std::isfinite(targetTopEdgeMetres))
    throw Error("bench-real: the target's top edge must be > 0 m");
  if (!(focalPx > 0) || !std::isfinite(focalPx)) throw Error("bench-real: --focal must be > 0");
  if (!(cubeSideMetres > 0) || !std::isfinite(cubeSideMetres))
    throw Error("bench-real: the cube side must be > 0 m");
  if (passes < 1) throw Error("bench-real: --passes must be >= 1");
}

double percentileOf(std::vector<double> values, double q) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const double at = std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(at));
  const std::size_t hi = std::min(values.size() - 1, lo + 1);
  return values[lo] + (at - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

namespace {

struct Clip {
  std::vector<cv::Mat> frames;
  double fps = 25.0;
};

Clip readClip(const std::filesystem::path& clip, int count) {
  if (!std::filesystem::exists(clip))
    throw Error("bench-real: clip '" + clip.string() +
                "' not found (the shared real recordings, ../shared/data; pass --clip)");
  cv::VideoCapture video(clip.string());
  if (!video.isOpened()) throw Error("bench-real: cannot open '" + clip.string() + "' as a video");
  Clip c;
  const double fps = video.get(cv::CAP_PROP_FPS);
  if (fps > 0 && std::isfinite(fps)) c.fps = fps;
  for (cv::Mat f; (count <= 0 || static_cast<int>(c.frames.size()) < count) && video.read(f);)
    c.frames.push_back(f.clone());
  if (c.frames.empty()) throw Error("bench-real: '" + clip.string() + "' holds no frames");
  return c;
}

// Scores each tracked pose against the card: the grid (7x7 over the card, frame 0's pixels
// carried by the followed homography) and the cube (card pose).
struct CardScorer {
  const PinholeCamera& camera;
  const PlanarTargetTruth& truth;
  std::vector<Eigen::Vector3d> grid, cube;
  std::vector<cv::Point2f> gridInFrame0;

  CardScorer(const PinholeCamera& c, const PlanarTargetTruth& t, double cubeSide)
      : camera(c), truth(t) {
    const double w = t.target[1].x, h = t.target[3].y;
    const RigidPose& T0 = *t.poses[0];
    for (int i = 0; i < 7; ++i)
      for (int j = 0; j < 7; ++j) {
        grid.emplace_back(w * i / 6.0, h * j / 6.0, 0.0);
        const Eigen::Vector2d p = camera.project(T0, grid.back());
        gridInFrame0.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
      }
    // The cube stands on the card's centre, on the camera's side of the card's plane.
    const double up = T0.cameraCentre().z() < 0 ? -1.0 : 1.0;
    for (const Eigen::Vector3d& v : cubeVertices(cubeSide))
      cube.emplace_back(v.x() + 0.5 * w, v.y() + 0.5 * h, up * v.z());
  }

  // Appends frame k's grid and cube errors of `worldToCamera` to `run`; returns them (NaN where
  // the frame has no truth).
  std::pair<double, double> score(std::size_t k, const RigidPose& worldToCamera,
                                  RealFootageRun& run) const {
    double gridError = NAN, cubeError = NAN;
    if (truth.homographies[k]) {
      std::vector<cv::Point2f> carried;
      cv::perspectiveTransform(gridInFrame0, carried, cv::Mat(*truth.homographies[k]));
      double sum = 0;
      for (std::size_t i = 0; i < grid.size(); ++i) {
        const Eigen::Vector2d p = camera.project(worldToCamera, grid[i]);
        sum += std::hypot(p.x() - carried[i].x, p.y() - carried[i].y);
      }
      gridError = sum / static_cast<double>(grid.size());
      run.gridErrorPx.push_back(gridError);
    }
    if (truth.poses[k]) {
      double sum = 0;
      for (const Eigen::Vector3d& X : cube)
        sum += (camera.project(worldToCamera, X) - camera.project(*truth.poses[k], X)).norm();
      cubeError = sum / static_cast<double>(cube.size());
      run.cubeErrorPx.push_back(cubeError);
    }
    return {gridError, cubeError};
  }

  // RealFootageFrame's truth columns of frame k (distances to `referencePoses`' centres, the
  // refined corners and how far they lie from the homography's).
  RealFootageFrame truthOf(std::size_t k, const std::vector<RigidPose>& referencePoses) const {
    RealFootageFrame f;
    f.frame = static_cast<int>(k);
    f.cardCorners.fill(cv::Point2f(NAN, NAN));
    if (truth.poses[k])
      for (const RigidPose& r : referencePoses)
        f.referenceDistanceMm.push_back(1000.0 *
                                        (truth.poses[k]->cameraCentre() - r.cameraCentre()).norm());
    else
      f.referenceDistanceMm.assign(referencePoses.size(), NAN);
    if (truth.corners[k] && truth.refinedCorners[k]) {
      f.cardCorners = *truth.corners[k];
      double worst = 0;
      for (std::size_t i = 0; i < 4; ++i)
        worst = std::max(
            worst, static_cast<double>(cv::norm((*truth.refinedCorners[k])[i] - f.cardCorners[i])));
      f.truthCornerShiftPx = worst;
    }
    return f;
  }
};

}  // namespace

RealFootageResult runRealFootageBenchmark(const RealFootageOptions& o, const TrackerParams& params,
                                          const ReferencePreparerParams& prepareParams) {
  o.check();
  const int lastReference = *std::max_element(o.references.begin(), o.references.end());
  // The card is followed from frame 0 in order, so every frame up to the last one needed is read.
  const int needed = o.frames > 0 ? std::max(o.frames, lastReference + 1) : 0;
  const Clip clip = readClip(o.clip, needed);
  const std::vector<cv::Mat>& frames = clip.frames;
  if (lastReference >= static_cast<int>(frames.size()))
    throw Error("bench-real: reference frame " + std::to_string(lastReference) + " is past the " +
                std::to_string(frames.size()) + " frames of '" + o.clip.string() + "'");
  const int tracked = o.frames > 0 ? std::min<int>(o.frames, static_cast<int>(frames.size()))
                                   : static_cast<int>(frames.size());

  RealFootageResult result;
  result.frameSize = frames[0].size();
  result.clipFrames = static_cast<int>(frames.size());
  Eigen::Matrix3d K;
  K << o.focalPx, 0, (result.frameSize.width - 1) * 0.5, 0, o.focalPx,
      (result.frameSize.height - 1) * 0.5, 0, 0, 1;
  const PinholeCamera camera(K, result.frameSize);
  const PlanarTargetTruth truth =
      PlanarTargetTruth::follow(frames, camera, o.targetCorners, o.targetTopEdgeMetres);
  result.followedFrames = static_cast<int>(
      std::count_if(truth.poses.begin(), truth.poses.end(), [](const auto& p) { return !!p; }));
  result.aspectRatio = truth.aspectRatio;
  result.aspectRms = truth.aspectRms;
  if (!truth.poses[0]) throw Error("bench-real: the card was not found in frame 0");

  std::vector<ReferenceImage> images;
  std::vector<RigidPose> poses;
  for (int r : o.references) {
    const auto& pose = truth.poses[static_cast<std::size_t>(r)];
    if (!pose)
      throw Error("bench-real: reference frame " + std::to_string(r) +
                  " has no card pose (the card was not followed there)");
    images.push_back({frames[static_cast<std::size_t>(r)], "frame " + std::to_string(r)});
    poses.push_back(*pose);
    result.referenceBaselinesMm.push_back(
        1000.0 * (pose->cameraCentre() - poses.front().cameraCentre()).norm());
  }
  // The card is the clip's fiducial: its four-corner poses (under a guessed K) are treated as
  // marker poses, refined by preparation.refine_poses as `prepare --marker` would, not as given
  // poses of a stated accuracy (preparation.refine_given_poses).
  ReferencePreparerParams cardPreparation = prepareParams;
  cardPreparation.refineGivenPoses = prepareParams.refinePoses;
  const MultiPreparation prepared =
      MultiReferencePreparer(camera, cardPreparation).prepare(images, poses, "card corners");
  result.mapPoints = static_cast<int>(prepared.map.points.size());
  const CardScorer scorer(camera, truth, o.cubeSideMetres);

  result.reftrack.name = "reftrack 6-DOF";
  result.reftrack.frames = tracked;
  if (o.baseline) {
    result.baseline.emplace();
    result.baseline->name = "ORB+PnP+Kalman";
    result.baseline->frames = tracked;
  }
  const ReferenceMap firstPair = prepared.map.pair(0, 1);
  for (int pass = 0; pass < o.passes; ++pass) {
    const bool first = pass == 0;
    {
      MultiReferenceTracker tracker(prepared.map, params);
      RealFootageRun& run = result.reftrack;
      for (int k = 0; k < tracked; ++k) {
        const double cpu0 = threadCpuMs();
        const MultiReferenceResult m = tracker.process(frames[static_cast<std::size_t>(k)]);
        const double cpu = threadCpuMs() - cpu0;
        const PoseTrackingResult& r = m.tracking;
        const bool ok = r.state == TrackingState::Tracking && r.worldToCamera.has_value();
        if (ok) run.trackedCpuMs.push_back(cpu);
        if (!first) continue;
        for (const StageTiming& st : r.timings) run.stageMs[st.stage].push_back(st.ms);
        RealFootageFrame f = scorer.truthOf(static_cast<std::size_t>(k), poses);
        f.state = toString(r.state);
        f.message = r.message;
        f.referenceA = m.referenceA;
        f.referenceB = m.referenceB;
        f.corners = r.corners;
        f.matchesA = r.matchesA;
        f.matchesB = r.matchesB;
        f.threeView = r.threeView;
        f.inliers = r.inliers;
        if (ok) f.supportSdPx = r.supportSdPx;
        if (!ok) {
          ++run.noPose[r.message.substr(0, r.message.find(" ("))];
          run.perFrame.push_back(std::move(f));
          continue;
        }
        ++run.tracked;
        run.estimate.poses.push_back({k / clip.fps, *r.worldToCamera});
        std::tie(f.gridErrorPx, f.cubeErrorPx) =
            scorer.score(static_cast<std::size_t>(k), *r.worldToCamera, run);
        run.perFrame.push_back(std::move(f));
        result.rollingShutterReadout = r.rollingShutterReadout;
      }
    }
    if (!o.baseline) continue;
    OrbPnpKalmanParams baselineParams;
    baselineParams.dt = 1.0 / clip.fps;
    OrbPnpKalmanTracker baseline(firstPair, baselineParams);
    RealFootageRun& run = *result.baseline;
    for (int k = 0; k < tracked; ++k) {
      const double cpu0 = threadCpuMs();
      const std::optional<RigidPose> pose = baseline.process(frames[static_cast<std::size_t>(k)]);
      const double cpu = threadCpuMs() - cpu0;
      if (pose) run.trackedCpuMs.push_back(cpu);
      if (!first) continue;
      if (!pose) {
        ++run.noPose["no pose (too few PnP inliers so far)"];
        continue;
      }
      ++run.tracked;
      run.estimate.poses.push_back({k / clip.fps, *pose});
      scorer.score(static_cast<std::size_t>(k), *pose, run);
    }
  }
  return result;
}

void writeRealFootageFramesCsv(const RealFootageRun& run, const std::filesystem::path& file) {
  writeFileAtomically(file, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp);
    if (!out) throw Error("cannot write '" + file.string() + "'");
    const std::size_t references =
        run.perFrame.empty() ? 0 : run.perFrame[0].referenceDistanceMm.size();
    out << "frame,state,reference_a,reference_b,grid_px,cube_px";
    for (std::size_t r = 0; r < references; ++r) out << ",distance_ref" << r << "_mm";
    out << ",corners,matches_a,matches_b,three_view,inliers,support_sd_px,truth_corner_shift_px";
    for (int c = 0; c < 4; ++c) out << ",card_x" << c << ",card_y" << c;
    out << ",message\n";
    out << std::setprecision(10);
    for (const RealFootageFrame& f : run.perFrame) {
      out << f.frame << ',' << f.state << ',' << f.referenceA << ',' << f.referenceB << ','
          << f.gridErrorPx << ',' << f.cubeErrorPx;
      for (double d : f.referenceDistanceMm) out << ',' << d;
      out << ',' << f.corners << ',' << f.matchesA << ',' << f.matchesB << ',' << f.threeView << ','
          << f.inliers << ',' << f.supportSdPx << ',' << f.truthCornerShiftPx;
      for (const cv::Point2f& c : f.cardCorners) out << ',' << c.x << ',' << c.y;
      std::string message = f.message;
      std::replace(message.begin(), message.end(), '"', '\'');
      out << ",\"" << message << "\"\n";
    }
    if (!out.flush()) throw Error("cannot write '" + file.string() + "'");
  });
}

}  // namespace reftrack::app
