#pragma once
// MultiReferenceTracker (issue 13): the 6-DOF tracker over a map of N references. Per frame it
// runs the paper's two-reference PoseTracker on the pair of references best placed for the last
// pose (ReferenceSelector: position and viewing direction, with hysteresis), so the cost of a
// tracked frame does not grow with N; switching pairs hands the current pose over to the new
// pair's tracker (PoseTracker::seed), and when that fails the pair in use goes on. Pair trackers
// are made on first use and references.cached_trackers of them are kept. Not tracking: within
// references.reseed_frames of a loss the last pose seeds the pair in use; then every frame tries
// the paper's start near a reference (one pair per frame in turn), and when that fails, every
// relocalisation.attempt_every_frames-th frame the Relocaliser (when enabled and the map has a
// usable keypoint layer; else said once in `notice`) proposes a pose from anywhere in the mapped
// volume, which the pair best placed for it refines and verifies on the same frame.
#include <Eigen/Core>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/config/TrackerParams.hpp"
#include "engine/estimation/CornerVarianceModel.hpp"
#include "engine/estimation/MotionModel.hpp"
#include "engine/reference/MultiReferenceMap.hpp"
#include "engine/relocalisation/RecoveryStage.hpp"
#include "engine/relocalisation/RecoveryWork.hpp"
#include "engine/tracking/PoseTracker.hpp"

namespace reftrack {

struct RelocalisationReport {
  bool attempted = false;  // the relocaliser ran on this frame
  bool succeeded = false;  // ... and its candidate was verified by the pair tracker
  double ms = 0.0;         // time of the attempt (keypoints, matching, PnP, verification)
  double cpuMs = 0.0;      // ... the thread's CPU time of it
  double locateMs = 0.0, locateCpuMs = 0.0;  // Relocaliser::locate alone (no verification)
  int inliers = 0;                           // PnP inliers of the candidate
  // What stopped the attempt (the relocaliser's search stage, the seeded pass, the check by
  // correlation, a start rule) or Verified; None when there was no attempt.
  RecoveryStage stop = RecoveryStage::None;
  std::string message;
};

// The recovery while lost on one frame (re-seed, start near a reference, relocaliser): what it
// did and what the budget (relocalisation.budget_*) was charged for it.
struct RecoveryReport {
  bool ran = false;         // the frame was searched (not left alone by the budget, not blank)
  RecoveryWork work;        // the work, counted
  double modelledMs = 0.0;  // its modelled cost (RecoveryCostModel): the same on any machine
  double chargedMs = 0.0;   // what the budget was charged: modelledMs, or the budget clock's time
  double cpuMs = 0.0;       // the process CPU time it took, measured (reported, decides nothing)
  // Asked when the budget held only its reserve: how much the frame looks like a reference view
  // (SceneResemblance::score; NaN: not asked), and whether that let it spend the reserve.
  double resemblance = std::numeric_limits<double>::quiet_NaN();
  bool aheadOfBudget = false;
};

struct MultiReferenceResult {
  PoseTrackingResult tracking;           // T_Ak etc. relative to reference `referenceA`
  int referenceA = -1, referenceB = -1;  // the pair whose tracker gave `tracking` (-1: none)
  RelocalisationReport relocalisation;
  // The start near a reference on this frame: what stopped it (StartNoPose, SeededPass,
  // Correlation, DistinctiveCorners, KeypointSupport) or Verified; NotSearched or BlankFrame when
  // the recovery tried nothing on the frame; None when tracking needed no start.
  RecoveryStage start = RecoveryStage::None;
  RecoveryReport recovery;
  // Said once, with the first frame after construction or a parameter change: why the tracker
  // runs without relocalisation when it was asked for (a map with a thin or no keypoint layer).
  std::string notice;
  // The overlay error the pose covariance predicts for the overlay's points (setOverlayPoints;
  // PredictedOverlayError.hpp: rescaled a posteriori, times pose.predicted_error_scale); nullopt
  // unless tracking.
  std::optional<double> predictedErrorPx;
  // Tracking, but predictedErrorPx > pose.max_predicted_error_px: the pose is given and tracking
  // goes on from it, yet it should not be drawn as if exact; the reason says by how much.
  bool uncertain = false;
  std::string uncertainReason;
};

class MultiReferenceTracker {
 public:
  MultiReferenceTracker(MultiReferenceMap map, const TrackerParams& params,
                        PoseTrackerLimits limits = {});
  ~MultiReferenceTracker();

  // One frame (BGR or grey, the map's image size; throws reftrack::Error on another size).
  MultiReferenceResult process(const cv::Mat& frame);

  void setParams(const TrackerParams& params);  // takes effect on the next frame
  void setMotionModel(const ArMotionModel& model);
  void setCornerVarianceModel(const CornerVarianceModel& model);
  // Back to initialising, as a fresh tracker: the pair trackers' learned reliability is forgotten
  // too (so a reset tracker gives the same poses as a new one).
  void reset();
  // The object whose overlay error predictedErrorPx predicts: its points in the world frame (e.g.
  // the 8 vertices of the drawn cube). Empty: the 8 corners of the box of the map points' central
  // part (centralBoxCorners), the default.
  void setOverlayPoints(std::vector<Eigen::Vector3d> worldPoints);
  const std::vector<Eigen::Vector3d>& overlayPoints() const;
  const MultiReferenceMap& map() const;
  TrackingState state() const;
  std::pair<int, int> referencesInUse() const;  // (-1, -1) before the first pose
  int relocalisationAttempts() const;           // since construction
  // How the recovery while lost (re-seeds, starts near a reference, relocalisation) is charged to
  // its budget (relocalisation.budget_*). By default (an empty clock) the modelled cost of its
  // work as counted (RecoveryWork): every decision then depends on the frames and parameters
  // only, for recorded input. With a clock (milliseconds of CPU, e.g. processCpuMs for a live
  // camera) the time it measures: the budget then bounds the real cost on this machine, and the
  // decisions depend on its load. Takes effect on the next frame.
  void setBudgetClock(std::function<double()> cpuMs);
  // What the budget was charged since construction (ms, modelled or measured as above).
  double recoveryChargedMs() const;
  // Why relocalisation is unavailable (no usable keypoint layer, or turned off); empty when on.
  const std::string& relocalisationUnavailable() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reftrack
