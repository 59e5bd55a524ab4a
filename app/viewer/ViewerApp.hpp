#pragma once
// runViewer: the AR viewer loop behind `reftrack view` and `reftrack demo`. Each iteration takes
// the next frame from the source (on the grabber thread, or rendered here for sim:), runs the
// tracker, records the composited frame when recording, and draws video + overlay (+ the ImGui
// panels) — into a GLFW window, or headless into an off-screen framebuffer (OSMesa/EGL).
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/sources/FrameSourceFactory.hpp"
#include "app/viewer/FrameTracker.hpp"
#include "app/viewer/SoakMonitor.hpp"
#include "engine/calibration/CameraCalibrator.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {

struct ViewerOptions {
  std::string input;               // see openFrameSource
  std::filesystem::path camera;    // camera.yml; optional for sim: inputs
  std::filesystem::path poses;     // TUM trajectory replayed as the poses (optional)
  std::filesystem::path params;    // ViewerSettings / TrackerParams YAML (optional)
  std::filesystem::path model;     // OBJ drawn instead of the cube (optional)
  std::optional<double> cubeSize;  // overrides the overlay's size (and its size from the scene)
  // Overrides the overlay's base centre (world, metres; and its placement on the scene).
  std::optional<Eigen::Vector3d> cubeAt;
  bool debugOverlay = false;         // turns on the corners, matches and labels (OverlaySettings)
  std::filesystem::path record;      // MP4 to record from the first frame (optional)
  std::filesystem::path screenshot;  // PNG of the last drawn canvas (optional)
  bool headless = false;
  bool ui = false;     // headless: draw the ImGui panels too (the window always has them)
  int maxFrames = -1;  // stop after this many processed frames; -1: the whole source (headless)
                       // or until the window is closed
  cv::Size canvasSize{1280, 720};  // window size, and the headless canvas with --ui
  // Live camera calibration (`--calibrate BOARD`): shows the Calibration panel; without --camera
  // the overlay uses a 60-degree guess until the calibrated camera is put to use. Headless, every
  // frame is examined and auto-captured (every calibrateEvery frames), calibration runs at the end
  // and, with calibrationOut, the camera is written there (an error when calibration fails).
  std::string calibrateBoard;
  int calibrateEvery = 0;  // auto-capture every N frames; 0: off in the window, 1 headless
  std::filesystem::path calibrationOut;
  // Building a reference map live (`--marker DICT:ID:SIZE` or `--board BOARD`: the world
  // frame): shows the Map panel. Headless, `captureAt` (frame indices) are captured, the map is
  // built from them before the input is tracked from its first frame on the new map, and written
  // to mapOut (an error when any step fails).
  std::string mapMarker, mapBoard;
  // ... or no fiducial (`--unprepared`): the first two captures posed by their own matches, the
  // scale from mapBaseline (metres the camera moved between them; headless --capture-at needs
  // it, the window's Map panel has a field for it).
  bool mapUnprepared = false;
  double mapBaseline = 0.0;
  std::vector<int> captureAt;
  std::filesystem::path mapOut;
  bool mapping() const { return !mapMarker.empty() || !mapBoard.empty() || mapUnprepared; }
  // Headless: the tracked poses as a TUM trajectory (camera in world), written atomically.
  std::filesystem::path trajectory;
  FrameSourceOptions source;
  // Headless soak report (`--report-every N`): resident memory and frame rate every N frames,
  // and the growth / rate ratio after the first soakWarmup frames. 0: off.
  int reportEvery = 0;
  int loops = 1;  // play a video file / image folder this many times (`--loop N`)
  int soakWarmup = 1000;
  // TUM ground truth of the frames (optional; `--gt`): with a live tracker, the Stats panel plots
  // the overlay's true error beside the predicted one. sim: inputs bring their own.
  std::filesystem::path groundTruth;
  // Builds the live tracker (homography / 6-DOF) for the camera; used when --poses is not given.
  // Unset: sim: inputs replay their ground truth, other inputs show the video only.
  std::function<std::unique_ptr<FrameTracker>(const PinholeCamera&, const TrackerParams&)>
      makeTracker;
  // The tracking mode to start in, over the params file's (`view` sets it when only one of
  // --map / --reference is given).
  std::optional<TrackingMode> mode;
  // `--realtime`: the 6-DOF search after a loss is budgeted in measured CPU time, as for a live
  // camera (always so for a live source), instead of the modelled cost of its work.
  bool realtime = false;
  void check() const;  // throws reftrack::Error naming the bad option
};

struct ViewerRunSummary {
  int framesProcessed = 0;
  double seconds = 0.0;
  double sourceFps = 0.0;
  std::string backend;  // "glfw-window", "osmesa", "egl-surfaceless"
  std::filesystem::path recording, trajectory, screenshot;  // empty when not written
  // Live calibration (with calibrateBoard): views captured and rejected, and the headless
  // end-of-run calibration (or why it failed).
  int calibrationCaptured = 0, calibrationRejected = 0;
  std::optional<CalibrationResult> calibration;
  std::string calibrationMessage;
  std::filesystem::path calibrationFile;  // the camera written (calibrationOut), else empty
  std::optional<SoakSummary> soak;        // with reportEvery
  // Live mapping (with mapMarker / mapBoard): the captured references (frame index, the
  // world->camera pose from the fiducial or tracking, its corner RMS; -1 when tracked), the map
  // built (references, points) and the files written.
  struct Capture {
    int frameIndex = -1;
    double timestamp = 0.0;
    RigidPose worldToCamera;
    std::string poseFrom;
    double fiducialRmsPx = -1.0;
  };
  std::vector<Capture> captures;
  int mapReferences = 0;
  std::size_t mapPoints = 0;
  std::string mapMessage;
  std::filesystem::path mapFolder, trajectoryFile;  // written, else empty
  int trackedFrames = 0;                            // frames with a pose
  // The overlay error of the drawn cube over the processed frames (the Stats panel's "pred" and
  // "true" curves): the mean predicted from the pose covariance over the frames with a
  // prediction, and the mean true one over the frames with ground truth (--gt, sim:).
  int predictedErrorFrames = 0, trueErrorFrames = 0;
  double predictedErrorMeanPx = 0.0, trueErrorMeanPx = 0.0;
};

// Runs the viewer. `context`: an existing current context to use (a GlfwWindowContext for the
// window path; any context headless); nullptr creates one. Throws reftrack::Error for bad input
// (missing files, camera size mismatch, unreadable frames); outputs are then left unwritten.
ViewerRunSummary runViewer(const ViewerOptions& options, render::GlContext* context = nullptr);

// True when DISPLAY or WAYLAND_DISPLAY is set (a window may be opened).
bool windowSystemAvailable();

}  // namespace reftrack::app
