#pragma once
// BoardPoseEstimator: the world->camera pose of an image from a calibration board in view (the
// board's frame is the world: origin at its first inner corner, x along a row, y down the
// columns, z = 0 on the board; CalibrationBoard). BoardDetector finds the corners, which are
// undistorted and solved by PnP (planar IPPE start, Levenberg-Marquardt refinement). A chessboard
// with COLS + ROWS odd is read from the end whose outer square is black (no 180-degree flip).
#include <optional>
#include <string>

#include "engine/calibration/BoardDetector.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

struct BoardPose {
  RigidPose worldToCamera;
  double reprojectionRmsPx = 0.0;  // of the corners under worldToCamera (ideal pixels)
  int corners = 0;                 // corners used
};

class BoardPoseEstimator {
 public:
  // Throws reftrack::Error on an invalid board or camera.
  BoardPoseEstimator(CalibrationBoard board, PinholeCamera camera,
                     double maxReprojectionRmsPx = 2.0);
  // Nothing when the board is not in view (`why`, if given, then says so). Throws
  // reftrack::Error naming `imageName` when the corners solve to a pose behind the camera or
  // reproject worse than maxReprojectionRmsPx (wrong camera or board).
  std::optional<BoardPose> estimate(const cv::Mat& image, const std::string& imageName,
                                    std::string* why = nullptr) const;

  const CalibrationBoard& board() const { return detector_.board(); }

 private:
  BoardDetector detector_;
  PinholeCamera camera_;
  double maxRmsPx_;
};

}  // namespace reftrack
