#pragma once
// KeypointMeasurer (issue 33): the map's keypoint layer measured in every tracked frame, beside
// the corner points. Each keypoint with a 3D point is projected with a pose good to a pixel or so
// (the frame's robust linear pose), the reference window around it warped into the frame by the
// local affine map that the projections of its nearest neighbours in that reference give (as
// PoseVerifier warps its windows), and aligned to the frame by Lucas-Kanade with bias and gain
// (PatchAligner): the measurement is where the reference's keypoint lies in the frame, to a
// fraction of a pixel, with no frame corner needed there. Points are visited in a fixed shuffled
// order, so that any prefix (the cap per frame) is spread at random over the scene.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/matching/PatchAligner.hpp"

namespace reftrack {

struct MeasurableKeypoint {
  Eigen::Vector3d pointA;  // its 3D point in camera A's frame
  cv::Point2f pixel;       // where the reference detected it (lens distortion kept)
  int reference = 0;       // 0: A, 1: B
};

struct KeypointMeasurement {
  int point = -1;         // index into the measurer's points
  cv::Point2f pixel;      // aligned frame pixel (lens distortion kept)
  cv::Point2f predicted;  // the projection the alignment started from
  double sigmaPx = 0.0;   // PatchAlignment::sigmaPx
};

class KeypointMeasurer {
 public:
  // grays: reference A and B (CV_8UC1, the camera's size).
  KeypointMeasurer(PinholeCamera camera, std::vector<MeasurableKeypoint> points,
                   const cv::Mat& grayA, const cv::Mat& grayB, PatchAlignerParams params);

  // The points T_Ak (reference A -> frame camera) projects into the frame (CV_8UC1), aligned
  // there; at most `cap` alignments are tried (0: every point). Both references' points are
  // measured: their layers mostly hold the same scene points (triangulated from their A <-> B
  // keypoint matches), and the two templates' measurements of a point, each consistent with its
  // own reference's keypoint pixel, average out the two pixels' disagreement with the point.
  // The alignments are split over OpenCV's threads; the result does not depend on their number.
  std::vector<KeypointMeasurement> measure(const cv::Mat& gray8, const RigidPose& T_Ak,
                                           int cap) const;

  // Drops the points whose window, aligned into the other reference (T_AB: reference A -> B) at
  // their projection there, fails: a keypoint match on repeated texture triangulates a point no
  // frame confirms, yet each is tried in every frame. Points not tried there (out of its view, no
  // local warp) stay. Returns how many were dropped; the indices of points() change.
  int dropPointsFailingBetweenReferences(const RigidPose& T_AB);

  const std::vector<MeasurableKeypoint>& points() const { return points_; }

 private:
  PinholeCamera camera_;
  std::vector<MeasurableKeypoint> points_;
  cv::Mat grays_[2];
  std::vector<std::vector<int>> neighbours_;  // per point: nearest points of its reference
  std::vector<int> order_;
  PatchAlignerParams alignerParams_;  // each measure() share aligns with its own PatchAligner

  void index();  // neighbours_ and order_ for points_
  // measure() of one reference's points (`reference` 0 / 1; -1: both); `tried` (when given, one
  // per point) marks the points whose alignment was tried.
  std::vector<KeypointMeasurement> measure(const cv::Mat& gray8, const RigidPose& T_Ak, int cap,
                                           int reference, std::vector<char>* tried) const;
};

}  // namespace reftrack
