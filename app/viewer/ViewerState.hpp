#pragma once
// ViewerState: everything the ImGui panels show and edit, owned by the viewer loop. Panels set
// requests (step, seek, start recording, ...); the loop carries them out and reports back.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "app/viewer/OverlayPanel.hpp"
#include "app/viewer/ReferencesPanel.hpp"
#include "app/viewer/StatsHistory.hpp"
#include "app/viewer/ViewerSettings.hpp"
#include "engine/calibration/CameraCalibrator.hpp"

namespace reftrack::app {

struct SourceState {
  // Shown.
  std::string description;
  std::optional<int> frameCount;
  int currentIndex = -1;
  double fps = 30.0;
  bool seekable = false, live = false, ended = false;
  std::size_t droppedFrames = 0;
  std::optional<std::string> disconnected;  // a live camera that stopped: why (reconnecting)
  // Edited.
  bool playing = true;
  bool loop = false;
  float speed = 1.0f;  // playback rate relative to the source's fps (window only)
  bool stepRequested = false;
  std::optional<int> seekRequest;
};

struct RecordState {
  std::string path = "recording.mp4";
  bool recording = false;
  bool startRequested = false, stopRequested = false;
  int framesWritten = 0;
  std::string message;  // last result or error
};

// The Calibration panel (live camera calibration, engine CalibrationSession).
struct CalibrationState {
  bool active = false;  // the panel is shown (`view --calibrate BOARD`)
  // Edited.
  std::string boardText = "chessboard:9x6:0.025";  // same syntax as `calibrate --board`
  bool autoCapture = false;
  int autoCaptureEvery = 15;  // frames between automatic captures while the board is found
  std::string savePath = "camera.yml";
  bool applyBoardRequested = false, captureRequested = false, clearRequested = false;
  bool calibrateRequested = false, saveRequested = false, useForTrackingRequested = false;
  // Shown.
  std::string board;  // the board in use
  int captured = 0, rejected = 0;
  std::string lastRejection;
  double coverage = 0.0;    // fraction of coverage cells touched by captured corners
  int currentCorners = -1;  // board corners found in the latest analysed frame; -1: none yet
  bool capturePending = false;
  bool calibrating = false;
  std::optional<CalibrationResult> result;
  bool usedForTracking = false;
  std::string message;  // last action's result or error
};

// A reference captured in the Map panel (LiveMapping).
struct MapCapture {
  int frameIndex = -1;
  double timestamp = 0.0;
  std::string poseFrom;         // "marker", "board" or "tracking"
  double fiducialRmsPx = -1.0;  // the marker's / board's corner reprojection RMS; -1: tracked
  bool inMap = false;           // built into the map, or added to it
  std::string note;             // why Add to map left it out
  unsigned int thumbnail = 0;   // GL texture id (0: none)
};

// Two captures: how far apart, and a warning when they are too close or turned too far to
// triangulate (the preparation's min_baseline_m and max_pair_view_angle_deg).
struct MapCapturePair {
  int a = -1, b = -1;
  double distanceMetres = 0.0, angleDeg = 0.0;
  std::string warning;  // empty: fine
};

// The Map panel (`view --marker SPEC` or `--board SPEC`: build a reference map live; `view
// --unprepared`: from two captures of an unprepared scene and the distance between them).
struct MapState {
  bool active = false;
  std::string fiducial;     // what fixes the world frame ("marker DICT_6X6_250:23:0.2")
  bool unprepared = false;  // no fiducial: the first two captures are posed by their own matches
  // Edited.
  std::string savePath = "map";
  // Unprepared: how far the camera moved between the first two captures (metres; 0: not given).
  double baselineMetres = 0.0;
  bool captureRequested = false, buildRequested = false, addRequested = false;
  bool saveRequested = false, clearRequested = false;
  // Shown.
  std::vector<MapCapture> captures;
  std::vector<MapCapturePair> pairs;
  cv::Size thumbnailSize{0, 0};
  bool working = false;  // building or adding on the worker thread
  std::string workLabel;
  float progress = 0.0f;     // of the work, 0..1
  std::string progressText;  // on the bar: steps done and seconds so far
  int mapReferences = 0;     // 0: no map yet
  std::size_t mapPoints = 0;
  bool tracking = false;  // the live tracker runs on this map
  // Unprepared, one capture and no map yet: how the camera moved since it (TwoViewMotion of the
  // capture and a recent frame), whether those two views could start a map, and the frame.
  std::string motion;  // empty: not measured yet
  bool motionUsable = false;
  int motionFrame = -1;
  std::string message;  // last action's result or error
  bool messageIsError = false;
};

struct ViewerState {
  SourceState source;
  ViewerSettings settings;
  OverlayPanelEdit overlayEdit;
  std::string trackerName;
  bool trackerParamsChanged = false;  // set by the Tracking panel; the loop applies them
  std::string paramsPath = "reftrack_params.yml";
  std::string paramsMessage;
  std::string lastStatus;
  std::optional<double> rollingShutterReadout;  // the 6-DOF tracker's, last frame
  StatsHistory stats;
  RecordState record;
  CalibrationState calibration;
  ReferencesState references;
  MapState map;
};

}  // namespace reftrack::app
