#pragma once
// CameraCalibrator: OpenCV camera calibration (cv::calibrateCamera) from views of a
// CalibrationBoard. Images where the board is not found are rejected and listed; when more views
// are found than maxViews, a spread-out subset is kept (greedy farthest-point selection over the
// board's image position, apparent size and tilt), so near-duplicate video frames do not dominate.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "engine/calibration/BoardDetector.hpp"
#include "engine/geometry/PinholeCamera.hpp"

namespace reftrack {

struct CalibrationParams {
  int minViews = 4;             // fewer usable views than this is an error
  int maxViews = 30;            // at most this many views enter cv::calibrateCamera
  bool fixAspectRatio = false;  // fx = fy (cv::CALIB_FIX_ASPECT_RATIO)
  bool zeroTangent = false;     // p1 = p2 = 0 (cv::CALIB_ZERO_TANGENT_DIST)
  bool fixK3 = false;           // k3 = 0 (cv::CALIB_FIX_K3)

  void check() const;  // throws reftrack::Error naming the bad field
};

struct CalibrationViewError {
  std::string label;
  int corners = 0;
  double rmsPx = 0.0;  // RMS reprojection error of this view's corners
};

struct CalibrationResult {
  PinholeCamera camera;
  double rmsPx = 0.0;                       // overall RMS reprojection error
  std::vector<CalibrationViewError> views;  // the views used, in input order
  std::vector<std::string> rejected;        // images where the board was not found
  std::size_t imagesExamined = 0, viewsFound = 0;
};

class CameraCalibrator {
 public:
  CameraCalibrator(CalibrationBoard board, CalibrationParams params = {});

  // Detects the board in `image`; returns whether it was found. Every image must have the size
  // of the first one (throws reftrack::Error naming the label otherwise).
  bool addImage(const cv::Mat& image, const std::string& label);
  // Adds a board already detected (BoardDetector) in an image of `imageSize`, under the same
  // size rule as addImage; for callers that detect elsewhere (the live calibration session).
  void addObservation(BoardObservation observation, cv::Size imageSize, const std::string& label);

  // Throws reftrack::Error when no view or too few views were found, or calibration fails.
  CalibrationResult calibrate() const;

 private:
  struct View {
    std::string label;
    BoardObservation observation;
  };
  std::vector<std::size_t> selectSpreadViews() const;
  void checkImageSize(cv::Size size, const std::string& label);

  BoardDetector detector_;
  CalibrationParams params_;
  cv::Size imageSize_{0, 0};
  std::vector<View> views_;
  std::vector<std::string> rejected_;
  std::size_t examined_ = 0;
};

}  // namespace reftrack
