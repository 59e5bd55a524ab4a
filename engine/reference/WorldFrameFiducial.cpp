#include "engine/reference/WorldFrameFiducial.hpp"

#include "engine/core/Error.hpp"

namespace reftrack {

WorldFrameFiducial WorldFrameFiducial::marker(const MarkerSpec& marker, const PinholeCamera& camera,
                                              const MarkerPoseParams& params) {
  marker.check();
  WorldFrameFiducial f;
  f.marker_ = std::make_shared<const MarkerPoseEstimator>(marker, camera, params);
  f.description_ = "marker " + marker.toString();
  return f;
}

WorldFrameFiducial WorldFrameFiducial::board(const CalibrationBoard& board,
                                             const PinholeCamera& camera) {
  WorldFrameFiducial f;
  f.board_ = std::make_shared<const BoardPoseEstimator>(board, camera);
  f.description_ = "board " + board.toString();
  return f;
}

std::optional<MeasuredPose> WorldFrameFiducial::estimate(const cv::Mat& image,
                                                         const std::string& imageName,
                                                         std::string& why) const {
  why.clear();
  try {
    if (marker_) {
      const MarkerPose p = marker_->estimate(image, imageName);
      return MeasuredPose{p.worldToCamera, p.reprojectionRmsPx};
    }
    const std::optional<BoardPose> p = board_->estimate(image, imageName, &why);
    if (!p) return std::nullopt;
    return MeasuredPose{p->worldToCamera, p->reprojectionRmsPx};
  } catch (const Error& e) {
    why = e.what();
    return std::nullopt;
  }
}

}  // namespace reftrack
