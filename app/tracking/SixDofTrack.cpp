#include "app/tracking/SixDofTrack.hpp"

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <map>
#include <sstream>

#include "app/cli/Interruption.hpp"
#include "app/cli/ProgressBar.hpp"
#include "app/tracking/TrackInput.hpp"
#include "app/viewer/OverlayCompositor.hpp"
#include "app/viewer/PoseFrameTracker.hpp"
#include "app/viewer/VideoRecorder.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/TumTrajectory.hpp"
#include "engine/mapping/ScenePlacement.hpp"
#include "engine/reference/MultiReferenceMap.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {

namespace {

// PoseTracker's stages in the order they run (a frame runs frame-to-frame or seed or initialise).
const char* kStages[] = {"corners", "frame-to-frame", "seed",    "initialise", "frame windows",
                         "match A", "match B",        "measure", "outliers",   "keypoints",
                         "pose",    "verify",         "confirm"};

// A CSV field: quoted, inner quotes doubled (messages hold commas).
std::string quoted(const std::string& text) {
  std::string q = "\"";
  for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string csvHeader() {
  std::string h =
      "index,timestamp,status,tx,ty,tz,qx,qy,qz,qw,corners,matches_a,matches_b,three_view,"
      "inliers,distinctive_inliers,ms_total,reference_a,reference_b,reloc_attempted,reloc_"
      "succeeded,reloc_ms,"
      "rolling_shutter_readout";
  for (const char* s : kStages) {
    std::string name = s;
    std::replace(name.begin(), name.end(), ' ', '_');
    std::replace(name.begin(), name.end(), '-', '_');
    h += ",ms_" + name;
  }
  return h + ",predicted_error_px,message\n";
}

// The recorded cube: on the map's dominant plane and scaled to the scene unless --cube-at /
// --cube-edge say otherwise (a map without a plane: the world origin, a 0.1 m edge); printed.
OverlaySettings placeCube(const MultiReferenceMap& map, const SixDofTrackOptions& o) {
  OverlaySettings overlay;
  overlay.setDebugLayers(o.debugOverlay);
  overlay.onScene = !o.cubeAt;
  overlay.sizeFromScene = !o.cubeEdge;
  if (o.cubeAt) overlay.offset = *o.cubeAt;
  if (o.cubeEdge) overlay.size = *o.cubeEdge;
  std::optional<ScenePlacement> scene;
  if (overlay.onScene || overlay.sizeFromScene) {
    try {
      scene = placeOnDominantPlane(map);
    } catch (const Error& e) {
      std::string fallback = o.cubeAt ? "" : "stands at the world origin (see --cube-at)";
      if (!o.cubeEdge)
        fallback += std::string(o.cubeAt ? "" : ", ") + "has a 0.1 m edge (see --cube-edge)";
      std::fprintf(stderr, "note: %s: the cube %s\n", e.what(), fallback.c_str());
    }
  }
  overlay.applyScene(scene);
  const Eigen::Vector3d up = overlay.orientation.col(2);
  std::printf("cube: edge %.3f m%s, base centre (%.3f, %.3f, %.3f) m, up (%.2f, %.2f, %.2f)",
              overlay.size, scene && overlay.sizeFromScene ? " (scaled to the scene)" : "",
              overlay.offset.x(), overlay.offset.y(), overlay.offset.z(), up.x(), up.y(), up.z());
  if (scene && overlay.onScene)
    std::printf(
        " on the scene's plane (%d of the %d map points near the middle within %.1f mm, "
        "RMS %.1f mm)",
        scene->planePoints, scene->consideredPoints, scene->planeThresholdMetres * 1e3,
        scene->planeRmsMetres * 1e3);
  std::printf("\n");
  return overlay;
}

}  // namespace

int runSixDofTrack(const SixDofTrackOptions& o) {
  const MultiReferenceMap map = MultiReferenceMap::load(o.map);  // version 2, or 1 as N = 2
  TrackerParams params = o.params.empty() ? TrackerParams{} : TrackerParams::load(o.params);
  params.mode = TrackingMode::SixDof;
  if (!o.motion.empty()) params.pose.motionModelFile = o.motion.string();
  params.check();

  // One headless GL context for the simulator source and the recorded overlay.
  TrackInput input(o.input, map.camera.imageSize(), "the camera is calibrated for", o.maxFrames,
                   !o.record.empty());

  PoseFrameTracker tracker(map, params);
  const bool realTimeBudget = o.realtime || input.source().isLive();
  tracker.setRealTimeBudget(realTimeBudget);
  std::unique_ptr<OverlayCompositor> compositor;
  std::unique_ptr<VideoRecorder> recorder;
  const OverlaySettings overlay = placeCube(map, o);
  tracker.setOverlayPoints(overlay.cubeWorldVertices());  // the predicted error is the cube's
  if (!o.record.empty()) {
    compositor = std::make_unique<OverlayCompositor>();
    recorder =
        std::make_unique<VideoRecorder>(o.record, input.source().fps(), map.camera.imageSize());
  }

  std::ostringstream csv;
  csv << csvHeader() << std::setprecision(10);
  TumTrajectory trajectory;
  ProgressBar progress("track 6dof", static_cast<std::size_t>(input.expectedCount()));
  int processed = 0, tracked = 0, switches = 0, relocAttempts = 0, relocSucceeded = 0;
  int uncertain = 0;
  std::vector<double> predicted;                       // of the tracked frames
  double readout = params.pose.rollingShutterReadout;  // the last tracked frame's
  std::pair<int, int> lastPair{-1, -1};
  std::vector<double> ms, relocMs, locateCpuMs, relocCpuMs;
  // What stopped each way back (RecoveryStage), counted per attempt.
  std::map<std::string, int> startStops, relocStops;
  // Lost frames searched on the budget's reserve (they looked like the scene).
  int aheadOfBudget = 0;
  const InterruptibleWork interruptible;  // Ctrl-C ends the loop; the outputs are then finished
  while (!interruptRequested()) {
    const std::optional<Frame> frame = input.next();
    if (!frame) break;
    if (o.coldStarts) tracker.tracker().reset();
    const TrackingResult result = tracker.process(frame->image, frame->index, frame->timestamp);
    const MultiReferenceResult& multi = tracker.last();
    const PoseTrackingResult& r = multi.tracking;
    if (!multi.notice.empty()) {
      std::fprintf(stderr, "note: %s\n", multi.notice.c_str());
    }
    ms.push_back(r.totalMs);
    if (r.state == TrackingState::Tracking) {
      readout = r.rollingShutterReadout;
      const std::pair<int, int> pair{multi.referenceA, multi.referenceB};
      if (lastPair.first >= 0 && pair != lastPair) ++switches;
      lastPair = pair;
    }
    if (multi.relocalisation.attempted) {
      ++relocAttempts;
      relocSucceeded += multi.relocalisation.succeeded ? 1 : 0;
      relocMs.push_back(multi.relocalisation.ms);
      locateCpuMs.push_back(multi.relocalisation.locateCpuMs);
      relocCpuMs.push_back(multi.relocalisation.cpuMs);
      ++relocStops[toString(multi.relocalisation.stop)];
    }
    if (multi.start != RecoveryStage::None) ++startStops[toString(multi.start)];
    aheadOfBudget += multi.recovery.aheadOfBudget ? 1 : 0;
    // Issue 32: a pose whose predicted overlay error exceeds pose.max_predicted_error_px.
    const char* status = multi.uncertain ? "uncertain" : toString(r.state);
    uncertain += multi.uncertain ? 1 : 0;
    if (multi.predictedErrorPx) predicted.push_back(*multi.predictedErrorPx);
    csv << frame->index << ',' << std::to_string(frame->timestamp) << ',' << status;
    if (r.worldToCamera) {
      ++tracked;
      trajectory.poses.push_back({frame->timestamp, *r.worldToCamera});
      const RigidPose camInWorld = r.worldToCamera->inverse();
      const Eigen::Quaterniond q(camInWorld.rotation());
      const Eigen::Vector3d c = camInWorld.translation();
      csv << ',' << c.x() << ',' << c.y() << ',' << c.z() << ',' << q.x() << ',' << q.y() << ','
          << q.z() << ',' << q.w();
    } else {
      csv << ",,,,,,,";
    }
    csv << ',' << r.corners << ',' << r.matchesA << ',' << r.matchesB << ',' << r.threeView << ','
        << r.inliers << ',' << r.distinctiveInliers << ',' << r.totalMs << ',' << multi.referenceA
        << ',' << multi.referenceB << ',' << (multi.relocalisation.attempted ? 1 : 0) << ','
        << (multi.relocalisation.succeeded ? 1 : 0) << ',' << multi.relocalisation.ms << ','
        << r.rollingShutterReadout;
    for (const char* s : kStages) {
      csv << ',';
      for (const StageTiming& t : r.timings)
        if (t.stage == s) csv << t.ms;
    }
    csv << ',';
    if (multi.predictedErrorPx) csv << *multi.predictedErrorPx;
    const std::string message = multi.uncertain                      ? multi.uncertainReason
                                : r.state == TrackingState::Tracking ? ""
                                                                     : r.message;
    csv << ',' << quoted(message) << '\n';
    if (recorder) {
      const cv::Mat composite =
          compositor->composite(frame->image, map.camera, result, overlay,
                                "frame " + std::to_string(frame->index) + "  " + result.status);
      recorder->write(composite, frame->timestamp, r.worldToCamera);
    }
    ++processed;
    progress.advance();
  }
  progress.finish();
  input.requireFrames();
  // A recording that cannot be finished (full disk) must not cost the other outputs.
  const std::string recordingError = closeRecording(recorder.get());
  if (!o.trajectory.empty()) trajectory.save(o.trajectory);
  if (!o.csv.empty())
    writeFileAtomically(o.csv, [&](const std::filesystem::path& tmp) {
      std::FILE* f = std::fopen(tmp.c_str(), "w");
      if (!f) throw Error("cannot write " + o.csv.string());
      const std::string text = csv.str();
      const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
      if (std::fclose(f) != 0 || !ok) throw Error("cannot write " + o.csv.string());
    });
  if (!recordingError.empty()) throw Error(recordingError);
  input.throwIfCutShort();
  std::nth_element(ms.begin(), ms.begin() + static_cast<long>(ms.size() / 2), ms.end());
  std::printf("6dof: %d frames, %d tracked (%.1f%%), median %.2f ms per frame\n", processed,
              tracked, 100.0 * tracked / processed, ms[ms.size() / 2]);
  std::printf("references: %d in the map, %d pair switches\n", map.size(), switches);
  if (!predicted.empty()) {
    std::sort(predicted.begin(), predicted.end());
    std::printf(
        "predicted overlay error (cube of %.3f m): median %.2f px, max %.2f px; %d frame(s) "
        "uncertain (above pose.max_predicted_error_px %g, 0: off)\n",
        overlay.size, predicted[predicted.size() / 2], predicted.back(), uncertain,
        params.pose.maxPredictedErrorPx);
  }
  std::printf("rolling-shutter readout: %.3f of the frame interval (%s)\n", readout,
              params.pose.estimateRollingShutter ? "estimated online, pose.estimate_rolling_shutter"
                                                 : "pose.rolling_shutter_readout");
  if (relocAttempts > 0) {
    const auto median = [](std::vector<double> v) {
      std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
      return v[v.size() / 2];
    };
    std::printf(
        "relocalisation: %d attempts, %d verified, median %.1f ms per attempt (wall clock; the "
        "search alone %.1f ms CPU); the recovery while lost: %.2f s %s in all "
        "(relocalisation.budget_ms_per_frame %g after a burst of %g ms)\n",
        relocAttempts, relocSucceeded, median(relocMs), median(locateCpuMs),
        tracker.tracker().recoveryChargedMs() / 1000.0,
        realTimeBudget ? "CPU (measured: a live source or --realtime)"
                       : "of modelled work (the same every run; --realtime: measured CPU)",
        params.relocalisation.budgetMsPerFrame, params.relocalisation.budgetBurstMs);
    std::printf(
        "relocalisation CPU of this thread (the whole cost with --threads 1): median %.1f ms per "
        "attempt with its verification\n",
        median(relocCpuMs));
  }
  const auto breakdown = [](const std::map<std::string, int>& stops) {
    std::string text;
    for (const auto& [stage, n] : stops)
      text += (text.empty() ? "" : ", ") + stage + " " + std::to_string(n);
    return text;
  };
  if (!startStops.empty())
    std::printf("recovery while not tracking, per frame, the start near a reference: %s\n",
                breakdown(startStops).c_str());
  if (aheadOfBudget > 0)
    std::printf(
        "recovery: %d lost frame(s) searched on the budget's reserve: they looked like the "
        "references (relocalisation.resemblance_min_score)\n",
        aheadOfBudget);
  if (!relocStops.empty())
    std::printf("relocalisation attempts, what stopped each: %s\n", breakdown(relocStops).c_str());
  if (!o.trajectory.empty()) std::printf("trajectory: %s\n", o.trajectory.string().c_str());
  if (!o.csv.empty()) std::printf("per-frame CSV: %s\n", o.csv.string().c_str());
  if (recorder) std::printf("recording: %s\n", o.record.string().c_str());
  return processed;
}

}  // namespace reftrack::app
