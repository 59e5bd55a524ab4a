#pragma once
// LiveCalibration: the viewer's side of live camera calibration. Owns the engine's
// CalibrationSession, looks for the board in the frames (on a worker thread in the window, in
// line headless), carries out the Calibration panel's requests (capture, auto-capture, clear,
// calibrate - on a worker thread in the window -, save, use for tracking), reports back into
// CalibrationState, and draws the coverage grid and the latest detected corners over the video.
#include <future>
#include <memory>
#include <optional>

#include "app/sources/FrameSource.hpp"
#include "app/viewer/ViewerState.hpp"
#include "engine/calibration/CalibrationSession.hpp"
#include "render/PixelCanvas.hpp"

namespace reftrack::app {

class LiveCalibration {
 public:
  // Starts with the board in state.boardText (throws reftrack::Error when it is invalid).
  // `background`: detect and calibrate on worker threads so the UI never waits.
  LiveCalibration(cv::Size imageSize, bool background, CalibrationState& state);
  ~LiveCalibration();  // waits for running work
  LiveCalibration(const LiveCalibration&) = delete;
  LiveCalibration& operator=(const LiveCalibration&) = delete;

  // Once per loop iteration. `frameNumber` grows by one per processed frame (a new number means
  // a new frame). Carries out and clears the requests in `state`, and updates what it shows.
  void update(const Frame& frame, int frameNumber, CalibrationState& state);
  // Calibrates the captured views now (waiting for a running calibration first) and reports the
  // result or error in `state`; for the end of a headless run.
  void calibrateNow(CalibrationState& state);
  // The calibrated camera once the user chose "Use for tracking" (returned once).
  std::optional<PinholeCamera> takeCameraForTracking();

  const CalibrationSession& session() const { return session_; }

  // Draws the shaded coverage cells and the latest detected corners over the current viewport,
  // which shows the whole frame. Needs a current GL 3.3 context.
  void drawOverlay();

 private:
  struct Detection {
    int frameNumber = -1;
    int generation = 0;  // the board it was made for
    std::optional<BoardObservation> observation;
  };
  void applyBoard(CalibrationState& state);
  void handleDetection(Detection detection, CalibrationState& state);
  void offer(const Detection& detection, CalibrationState& state);
  void collectCalibration(CalibrationState& state);
  void report(CalibrationState& state) const;

  bool background_;
  CalibrationSession session_;
  int generation_ = 0;
  std::future<Detection> detecting_;
  std::future<CalibrationResult> calibrating_;
  int lastAnalysedFrame_ = -1;
  std::optional<int> captureFrom_;  // the first frame number a requested capture may use
  int lastAutoCapture_ = -1000000;
  std::optional<Detection> latest_;
  std::optional<PinholeCamera> cameraForTracking_;
  std::unique_ptr<render::PixelCanvas> canvas_;
};

}  // namespace reftrack::app
