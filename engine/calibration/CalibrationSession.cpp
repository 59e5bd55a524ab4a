#include "engine/calibration/CalibrationSession.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/config/ConfigValue.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

// Image points indexed by board corner (row-major over the corner grid); NaN where missing.
std::vector<cv::Point2f> byCornerIndex(const BoardObservation& obs, const CalibrationBoard& board) {
  const cv::Size grid = board.cornerGrid();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<cv::Point2f> out(static_cast<std::size_t>(grid.area()), cv::Point2f(nan, nan));
  for (std::size_t k = 0; k < obs.objectPoints.size(); ++k) {
    const int ix = static_cast<int>(std::lround(obs.objectPoints[k].x / board.squareMetres));
    const int iy = static_cast<int>(std::lround(obs.objectPoints[k].y / board.squareMetres));
    if (ix >= 0 && iy >= 0 && ix < grid.width && iy < grid.height)
      out[static_cast<std::size_t>(iy * grid.width + ix)] = obs.imagePoints[k];
  }
  return out;
}

// Mean distance over the corners present in both; nullopt when fewer than 4 are shared.
// `rotated`: compare corner i of `a` with corner N-1-i of `b` (the board turned by 180 degrees,
// which a chessboard detector cannot tell apart).
std::optional<double> meanDisplacement(const std::vector<cv::Point2f>& a,
                                       const std::vector<cv::Point2f>& b, bool rotated) {
  double sum = 0.0;
  int shared = 0;
  const std::size_t n = a.size();
  for (std::size_t i = 0; i < n; ++i) {
    const cv::Point2f& p = a[i];
    const cv::Point2f& q = rotated ? b[n - 1 - i] : b[i];
    if (std::isnan(p.x) || std::isnan(q.x)) continue;
    sum += std::hypot(p.x - q.x, p.y - q.y);
    ++shared;
  }
  if (shared < 4) return std::nullopt;
  return sum / shared;
}

}  // namespace

void CalibrationSessionParams::check() const {
  if (!(std::isfinite(minMeanShift) && minMeanShift >= 0.0 && minMeanShift < 1.0))
    throw Error("calibration.min_mean_shift must be in [0, 1), got " +
                std::to_string(minMeanShift));
  requireIntInRange("calibration.coverage_grid.width", coverageGrid.width, 1, 100);
  requireIntInRange("calibration.coverage_grid.height", coverageGrid.height, 1, 100);
  calibration.check();
}

CalibrationSession::CalibrationSession(CalibrationBoard board, cv::Size imageSize,
                                       CalibrationSessionParams params)
    : detector_(std::move(board)), imageSize_(imageSize), params_(params) {
  params_.check();
  if (imageSize_.width < 8 || imageSize_.height < 8)
    throw Error("calibration: image size " + std::to_string(imageSize_.width) + "x" +
                std::to_string(imageSize_.height) + " is too small");
  clear();
}

CalibrationViewOutcome CalibrationSession::addView(const cv::Mat& image) {
  if (image.size() != imageSize_)
    throw Error("calibration: the image is " + std::to_string(image.cols) + "x" +
                std::to_string(image.rows) + " but the session is for " +
                std::to_string(imageSize_.width) + "x" + std::to_string(imageSize_.height));
  return addDetection(detector_.detect(image));
}

CalibrationViewOutcome CalibrationSession::addDetection(std::optional<BoardObservation> detection) {
  CalibrationViewOutcome out;
  if (!detection || detection->imagePoints.empty()) {
    out.reason = "board not found";
  } else if (detection->imagePoints.size() != detection->objectPoints.size()) {
    throw Error("calibration: the board observation has mismatched corner lists");
  } else {
    out.found = true;
    out.corners = static_cast<int>(detection->imagePoints.size());
    const double diagonal = std::hypot(imageSize_.width, imageSize_.height);
    const double minShift = params_.minMeanShift * diagonal;
    if (const auto nearest = nearestCapturedView(*detection);
        nearest && nearest->first < minShift) {
      char text[160];
      std::snprintf(text, sizeof text,
                    "too similar to view %d (corners moved %.1f px on average, need %.1f): move "
                    "or tilt the board",
                    nearest->second + 1, nearest->first, minShift);
      out.reason = text;
    } else {
      out.accepted = true;
    }
    out.observation = std::move(*detection);
  }
  if (!out.accepted) {
    ++rejected_;
    lastRejection_ = out.reason;
    return out;
  }
  const cv::Size grid = params_.coverageGrid;
  for (const cv::Point2f& p : out.observation.imagePoints) {
    const int cx =
        std::clamp(static_cast<int>(p.x * grid.width / imageSize_.width), 0, grid.width - 1);
    const int cy =
        std::clamp(static_cast<int>(p.y * grid.height / imageSize_.height), 0, grid.height - 1);
    ++cellCounts_[static_cast<std::size_t>(cy * grid.width + cx)];
  }
  views_.push_back(out.observation);
  return out;
}

std::optional<std::pair<double, int>> CalibrationSession::nearestCapturedView(
    const BoardObservation& obs) const {
  const CalibrationBoard& b = board();
  const std::vector<cv::Point2f> mine = byCornerIndex(obs, b);
  std::optional<std::pair<double, int>> best;
  for (std::size_t v = 0; v < views_.size(); ++v) {
    const std::vector<cv::Point2f> theirs = byCornerIndex(views_[v], b);
    for (bool rotated : {false, true}) {
      // ChArUco corners carry their identity (the marker ids); only a chessboard is symmetric.
      if (rotated && b.kind != CalibrationBoard::Kind::Chessboard) continue;
      const std::optional<double> d = meanDisplacement(mine, theirs, rotated);
      if (d && (!best || *d < best->first)) best = std::make_pair(*d, static_cast<int>(v));
    }
  }
  return best;
}

double CalibrationSession::coverage() const {
  const auto touched =
      std::count_if(cellCounts_.begin(), cellCounts_.end(), [](int count) { return count > 0; });
  return static_cast<double>(touched) / static_cast<double>(cellCounts_.size());
}

cv::Rect2f CalibrationSession::cell(int column, int row) const {
  const cv::Size grid = params_.coverageGrid;
  if (column < 0 || row < 0 || column >= grid.width || row >= grid.height)
    throw Error("calibration: coverage cell (" + std::to_string(column) + ", " +
                std::to_string(row) + ") is outside the grid");
  const float w = static_cast<float>(imageSize_.width) / grid.width;
  const float h = static_cast<float>(imageSize_.height) / grid.height;
  return {column * w, row * h, w, h};
}

CalibrationResult CalibrationSession::calibrate() const {
  if (capturedViews() < params_.calibration.minViews)
    throw Error("calibration needs at least " + std::to_string(params_.calibration.minViews) +
                " captured views of the board, have " + std::to_string(capturedViews()));
  CameraCalibrator calibrator(board(), params_.calibration);
  for (std::size_t i = 0; i < views_.size(); ++i)
    calibrator.addObservation(views_[i], imageSize_, "view " + std::to_string(i + 1));
  return calibrator.calibrate();
}

void CalibrationSession::save(const CalibrationResult& result, const std::filesystem::path& file) {
  if (file.empty()) throw Error("calibration: no file name to save the camera to");
  result.camera.save(file);
}

void CalibrationSession::clear() {
  views_.clear();
  cellCounts_.assign(static_cast<std::size_t>(params_.coverageGrid.area()), 0);
  rejected_ = 0;
  lastRejection_.clear();
}

}  // namespace reftrack
