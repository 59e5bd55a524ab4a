#pragma once
// `reftrack track --mode 6dof`: runs the MultiReferenceTracker over a frame source against a
// prepared reference map (N references, or a two-reference version-1 map) and writes the TUM
// trajectory of T_k, the per-frame CSV (status and reason, pose, counts, the pair of references
// in use, the relocalisation attempt, milliseconds per stage, the overlay error the covariance
// predicts for the recorded cube: predicted_error_px, empty when not tracking) and, optionally,
// the recorded overlay: the cube on the map's dominant plane (ScenePlacement) unless placed by
// hand, the tracker's debug layers only with debugOverlay. A frame above
// pose.max_predicted_error_px has status `uncertain` and the reason as its message; its pose is
// written (CSV and trajectory) but the recording draws the cube thin and grey (OverlayCompositor).
// Called by TrackCommand for the 6dof mode.
#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>

namespace reftrack::app {

struct SixDofTrackOptions {
  std::filesystem::path map;         // folder written by `reftrack prepare`
  std::string input;                 // video file, image folder/glob (as `view --input`)
  std::filesystem::path params;      // optional TrackerParams YAML
  std::filesystem::path motion;      // optional fitted motion model (fit-motion output)
  std::filesystem::path trajectory;  // TUM output (camera in world); empty = none
  std::filesystem::path csv;         // per-frame CSV; empty = none
  std::filesystem::path record;      // MP4 of the registered overlay; empty = none
  int maxFrames = -1;                // -1 = all
  // The recorded cube: by default on the map's dominant plane, scaled to the scene
  // (ScenePlacement); cubeAt puts its base centre there (world, metres, upright in the world
  // frame), cubeEdge sets its edge (metres).
  std::optional<Eigen::Vector3d> cubeAt;
  std::optional<double> cubeEdge;
  bool debugOverlay = false;  // the recording also shows corners, matches and the status label
  bool coldStarts = false;    // reset the tracker before every frame
  // The search after a loss is budgeted in measured CPU time (as a live camera always is)
  // instead of the modelled cost of its work, with which a file gives the same poses every run.
  bool realtime = false;
};

// Returns the number of frames processed; throws reftrack::Error on bad input.
int runSixDofTrack(const SixDofTrackOptions& options);

}  // namespace reftrack::app
