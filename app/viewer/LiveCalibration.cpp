#include "app/viewer/LiveCalibration.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <utility>

#include "app/viewer/BackgroundWork.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

LiveCalibration::LiveCalibration(cv::Size imageSize, bool background, CalibrationState& state)
    : background_(background), session_(CalibrationBoard::parse(state.boardText), imageSize) {
  state.board = session_.board().toString();
  report(state);
}

LiveCalibration::~LiveCalibration() {
  if (detecting_.valid()) detecting_.wait();
  if (calibrating_.valid()) calibrating_.wait();
}

void LiveCalibration::applyBoard(CalibrationState& state) {
  try {
    CalibrationSession fresh(CalibrationBoard::parse(state.boardText), session_.imageSize(),
                             session_.params());
    session_ = std::move(fresh);
    ++generation_;  // detections still running are for the old board
    latest_.reset();
    captureFrom_.reset();
    lastAnalysedFrame_ = -1;
    state.board = session_.board().toString();
    state.message = "board " + state.board + "; views cleared";
  } catch (const Error& e) {
    state.message = e.what();
  }
}

void LiveCalibration::update(const Frame& frame, int frameNumber, CalibrationState& state) {
  if (std::exchange(state.applyBoardRequested, false)) applyBoard(state);
  if (std::exchange(state.clearRequested, false)) {
    session_.clear();
    state.message = "views cleared";
  }
  if (std::exchange(state.captureRequested, false)) {
    if (latest_ && latest_->frameNumber == frameNumber)
      offer(*latest_, state);  // the current frame is analysed already (e.g. paused)
    else
      captureFrom_ = frameNumber;
  }

  // Look for the board: one detection at a time, always on the newest frame.
  if (ready(detecting_)) {
    try {
      handleDetection(detecting_.get(), state);
    } catch (const std::exception&) {
      handleDetection(Detection{lastAnalysedFrame_, generation_, std::nullopt}, state);
    }
  }
  if (frameNumber != lastAnalysedFrame_ && !detecting_.valid() && !frame.image.empty()) {
    lastAnalysedFrame_ = frameNumber;
    if (background_) {
      detecting_ = std::async(std::launch::async,
                              [detector = session_.detector(), image = frame.image.clone(),
                               frameNumber, generation = generation_] {
                                return Detection{frameNumber, generation, detector.detect(image)};
                              });
    } else {
      handleDetection(Detection{frameNumber, generation_, session_.detector().detect(frame.image)},
                      state);
    }
  }

  if (std::exchange(state.calibrateRequested, false) && !calibrating_.valid()) {
    state.message.clear();
    if (background_) {
      calibrating_ =
          std::async(std::launch::async, [session = session_] { return session.calibrate(); });
    } else {
      calibrateNow(state);
    }
  }
  if (ready(calibrating_)) collectCalibration(state);
  state.calibrating = calibrating_.valid();

  if (std::exchange(state.saveRequested, false)) {
    try {
      if (!state.result) throw Error("calibrate first: there is no camera to save");
      CalibrationSession::save(*state.result, state.savePath);
      state.message = "saved " + state.savePath;
    } catch (const Error& e) {
      state.message = e.what();
    } catch (const std::exception& e) {
      state.message = "saving '" + state.savePath + "' failed: " + e.what();
    }
  }
  if (std::exchange(state.useForTrackingRequested, false)) {
    if (state.result)
      cameraForTracking_ = state.result->camera;
    else
      state.message = "calibrate first: there is no camera to use";
  }
  report(state);
}

void LiveCalibration::handleDetection(Detection detection, CalibrationState& state) {
  if (detection.generation != generation_) return;
  latest_ = std::move(detection);
  const bool found = latest_->observation.has_value();
  state.currentCorners = found ? static_cast<int>(latest_->observation->imagePoints.size()) : 0;
  if (captureFrom_ && latest_->frameNumber >= *captureFrom_) {
    captureFrom_.reset();
    offer(*latest_, state);
  } else if (found && state.autoCapture &&
             latest_->frameNumber - lastAutoCapture_ >= std::max(1, state.autoCaptureEvery)) {
    lastAutoCapture_ = latest_->frameNumber;
    offer(*latest_, state);
  }
}

void LiveCalibration::offer(const Detection& detection, CalibrationState& state) {
  const CalibrationViewOutcome out = session_.addDetection(detection.observation);
  if (out.accepted)
    state.message = "captured view " + std::to_string(session_.capturedViews()) + " (" +
                    std::to_string(out.corners) + " corners)";
  else
    state.message.clear();  // the rejection's reason is shown as lastRejection
}

void LiveCalibration::calibrateNow(CalibrationState& state) {
  if (calibrating_.valid()) {
    calibrating_.wait();
    collectCalibration(state);
    return;
  }
  try {
    state.result = session_.calibrate();
    state.usedForTracking = false;
    state.message = "calibrated";
  } catch (const std::exception& e) {
    state.message = std::string("calibration failed: ") + e.what();
  }
  state.calibrating = false;
}

void LiveCalibration::collectCalibration(CalibrationState& state) {
  try {
    state.result = calibrating_.get();
    state.usedForTracking = false;
    state.message = "calibrated";
  } catch (...) {
    state.message = "calibration failed: " + errorText(std::current_exception());
  }
  state.calibrating = false;
}

std::optional<PinholeCamera> LiveCalibration::takeCameraForTracking() {
  return std::exchange(cameraForTracking_, std::nullopt);
}

void LiveCalibration::report(CalibrationState& state) const {
  state.captured = session_.capturedViews();
  state.rejected = session_.rejectedViews();
  state.lastRejection = session_.lastRejection();
  state.coverage = session_.coverage();
  state.capturePending = captureFrom_.has_value();
  if (!latest_) state.currentCorners = -1;
}

void LiveCalibration::drawOverlay() {
  if (!canvas_) canvas_ = std::make_unique<render::PixelCanvas>();
  canvas_->clear();
  const cv::Size size = session_.imageSize();
  const float scale = std::max(1.0f, size.height / 240.0f);
  const cv::Size grid = session_.params().coverageGrid;
  const std::vector<int>& counts = session_.cellCounts();
  // Covered cells in green, more opaque the more corners they hold (full at 20 corners).
  for (int row = 0; row < grid.height; ++row)
    for (int col = 0; col < grid.width; ++col) {
      const int count = counts[static_cast<std::size_t>(row * grid.width + col)];
      if (count == 0) continue;
      const cv::Rect2f c = session_.cell(col, row);
      const float x0 = c.x - 0.5f, y0 = c.y - 0.5f, x1 = x0 + c.width, y1 = y0 + c.height;
      const double alpha = 0.12 + 0.28 * std::min(1.0, count / 20.0);
      canvas_->addQuad({x0, y0}, {x1, y0}, {x1, y1}, {x0, y1},
                       render::rgbaFromBgr(cv::Scalar(60, 220, 60), alpha));
    }
  const Eigen::Vector4f gridColour = render::rgbaFromBgr(cv::Scalar(200, 200, 200), 0.35);
  for (int col = 1; col < grid.width; ++col) {
    const float x = session_.cell(col, 0).x - 0.5f;
    canvas_->addThickLine({x, -0.5f}, {x, size.height - 0.5f}, 1.0f, gridColour);
  }
  for (int row = 1; row < grid.height; ++row) {
    const float y = session_.cell(0, row).y - 0.5f;
    canvas_->addThickLine({-0.5f, y}, {size.width - 0.5f, y}, 1.0f, gridColour);
  }
  // The latest detection: its corners joined in order (like cv::drawChessboardCorners).
  if (latest_ && latest_->observation) {
    const std::vector<cv::Point2f>& pts = latest_->observation->imagePoints;
    const Eigen::Vector4f line = render::rgbaFromBgr(cv::Scalar(255, 160, 60), 0.8);
    const Eigen::Vector4f dot = render::rgbaFromBgr(cv::Scalar(0, 220, 255), 1.0);
    for (std::size_t i = 1; i < pts.size(); ++i)
      canvas_->addThickLine({pts[i - 1].x, pts[i - 1].y}, {pts[i].x, pts[i].y}, 0.6f * scale, line);
    for (const cv::Point2f& p : pts) canvas_->addDisc({p.x, p.y}, 1.8f * scale, dot);
  }
  canvas_->draw(size);
}

}  // namespace reftrack::app
