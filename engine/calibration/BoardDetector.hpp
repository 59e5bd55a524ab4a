#pragma once
// BoardDetector: finds a CalibrationBoard's inner corners in one image, to sub-pixel accuracy.
// Chessboards use cv::findChessboardCornersSB followed by cv::cornerSubPix; ChArUco boards detect
// the ArUco markers and interpolate the chessboard corners between them (all corners or a subset).
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "engine/calibration/CalibrationBoard.hpp"

namespace reftrack {

// The corners of one detected board: board-frame positions and their pixels.
struct BoardObservation {
  std::vector<cv::Point3f> objectPoints;
  std::vector<cv::Point2f> imagePoints;
};

class BoardDetector {
 public:
  explicit BoardDetector(CalibrationBoard board);
  // Nothing when the board is not found (or, for ChArUco, fewer than minCharucoCorners corners).
  // Accepts 8-bit grey or BGR images; throws reftrack::Error on an empty or other image type.
  std::optional<BoardObservation> detect(const cv::Mat& image) const;

  const CalibrationBoard& board() const { return board_; }
  int minCharucoCorners = 6;

 private:
  CalibrationBoard board_;
};

}  // namespace reftrack
