#pragma once
// CalibrationSession: interactive camera calibration (the viewer's Calibration panel). Views are
// offered one at a time; a view is captured when the board is found and it is not a near
// duplicate of a captured one (the board corners' mean displacement from every captured view
// must reach a fraction of the image diagonal), so the user is pushed to spread the views.
// Coverage counts the captured corners per cell of a grid over the image. calibrate() runs the
// CameraCalibrator on the captured views; the camera is saved as `reftrack calibrate` writes it.
// A value type: copy it to calibrate on another thread while this one keeps capturing.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/calibration/BoardDetector.hpp"
#include "engine/calibration/CameraCalibrator.hpp"

namespace reftrack {

struct CalibrationSessionParams {
  // A view whose corners moved on average less than this fraction of the image diagonal from
  // those of a captured view is rejected as too similar (640x480: 0.015 -> 12 px; two of the
  // hand-held OpenCV sample shots differ by 14.7 px, a board held still by 1-3 px).
  double minMeanShift = 0.015;
  cv::Size coverageGrid{8, 6};  // cells across x down
  CalibrationParams calibration;

  void check() const;  // throws reftrack::Error naming the bad field
};

// What became of one offered view.
struct CalibrationViewOutcome {
  bool found = false;            // the board was detected
  int corners = 0;               // detected corners
  bool accepted = false;         // captured as a calibration view
  std::string reason;            // why not accepted (empty when accepted)
  BoardObservation observation;  // the detected corners (empty when not found)
};

class CalibrationSession {
 public:
  // Throws reftrack::Error for an invalid board, params or image size.
  CalibrationSession(CalibrationBoard board, cv::Size imageSize,
                     CalibrationSessionParams params = {});

  // Detects the board in `image` (8-bit grey or BGR of imageSize()) and offers the result.
  CalibrationViewOutcome addView(const cv::Mat& image);
  // Offers a detection made elsewhere (e.g. BoardDetector on a worker thread) for an image of
  // imageSize(): nullopt means the board was not found.
  CalibrationViewOutcome addDetection(std::optional<BoardObservation> detection);

  const BoardDetector& detector() const { return detector_; }
  const CalibrationBoard& board() const { return detector_.board(); }
  cv::Size imageSize() const { return imageSize_; }
  const CalibrationSessionParams& params() const { return params_; }

  int capturedViews() const { return static_cast<int>(views_.size()); }
  int rejectedViews() const { return rejected_; }
  const std::string& lastRejection() const { return lastRejection_; }
  const std::vector<BoardObservation>& views() const { return views_; }

  // Captured corners per coverage cell, row-major over params().coverageGrid.
  const std::vector<int>& cellCounts() const { return cellCounts_; }
  // Fraction (0..1) of coverage cells holding at least one captured corner.
  double coverage() const;
  // The pixel rectangle of coverage cell (column, row).
  cv::Rect2f cell(int column, int row) const;

  // CameraCalibrator on the captured views (labelled "view 1", "view 2", ... in capture order).
  // Throws reftrack::Error when fewer than params().calibration.minViews were captured or
  // calibration fails.
  CalibrationResult calibrate() const;
  // Writes `result.camera` as camera.yml (the format `reftrack calibrate` writes; atomic).
  static void save(const CalibrationResult& result, const std::filesystem::path& file);

  void clear();  // forgets every view and count

 private:
  // The smallest mean corner displacement (pixels) from `obs` to a captured view, with the
  // index of that view; nullopt when no captured view shares at least 4 corners.
  std::optional<std::pair<double, int>> nearestCapturedView(const BoardObservation& obs) const;

  BoardDetector detector_;
  cv::Size imageSize_;
  CalibrationSessionParams params_;
  std::vector<BoardObservation> views_;
  std::vector<int> cellCounts_;
  int rejected_ = 0;
  std::string lastRejection_;
};

}  // namespace reftrack
