#pragma once
// CalibrationPanel: live camera calibration — the board (same syntax as `calibrate --board`),
// Capture view / auto-capture every N frames, captured and rejected counts with the last
// rejection's reason, coverage, Calibrate (RMS, fx fy cx cy, per-view errors), Save camera.yml and
// Use for tracking. It only sets requests in CalibrationState; LiveCalibration carries them out.
#include <opencv2/core.hpp>

#include "app/viewer/ViewerState.hpp"

namespace reftrack::app {

void drawCalibrationPanel(CalibrationState& state, const cv::Rect2f& placement);

}  // namespace reftrack::app
