#pragma once
// MarkerPoseEstimator: the world->camera pose of an image from one printed ArUco marker
// (detection with sub-pixel corners, IPPE-square PnP, Levenberg-Marquardt refinement).
// Throws reftrack::Error naming the image when the marker is missing, repeated or ambiguous.
#include <array>
#include <opencv2/core.hpp>
#include <string>

#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/MarkerSpec.hpp"

namespace reftrack {

struct MarkerPose {
  RigidPose worldToCamera;
  std::array<cv::Point2f, 4> cornersPixels;  // detected (distorted) corner pixels, aruco order
  double reprojectionRmsPx = 0.0;            // of the four corners under worldToCamera
  double alternativeRmsPx = 0.0;             // the other IPPE solution (planar flip ambiguity)
};

struct MarkerPoseParams {
  // Both IPPE solutions explain the corners within this ratio -> the pose is ambiguous.
  double ambiguityRatio = 1.2;
  // Reprojection RMS above this means the detection or the camera model is wrong.
  double maxReprojectionRmsPx = 2.0;
  void check() const;
};

class MarkerPoseEstimator {
 public:
  using Params = MarkerPoseParams;

  MarkerPoseEstimator(MarkerSpec marker, PinholeCamera camera, Params params = {});
  // `imageName` only labels error messages.
  MarkerPose estimate(const cv::Mat& image, const std::string& imageName) const;

 private:
  MarkerSpec marker_;
  PinholeCamera camera_;
  Params params_;
};

// Sub-pixel corners of a detected marker from straight-line fits to the four sides of its outer
// black square (the detector's corners seed it; returned unchanged if the fit fails).
std::array<cv::Point2f, 4> refineMarkerCorners(const cv::Mat& gray,
                                               const std::array<cv::Point2f, 4>& initial);

}  // namespace reftrack
