#pragma once
// PoseVerifier: the check every 6-DOF pose passes before it is reported, whatever produced it
// (frame-to-frame tracking, a seed, a start near a reference, a relocalisation). It trusts the
// pose alone, not the matches that produced it: at every distinctive map point (its corner has no
// look-alike near it in the reference: DistinctiveCorners) that the pose projects into the frame,
// the reference window around the point, warped by the pose (the local affine map that the
// projections of its neighbouring map points give), must correlate with the frame within a pixel
// or two of the projection. On repeated texture a pose a few periods off (a chessboard two
// squares away, reached from a prediction made before a cut) keeps its look-alike matches, but
// its distinctive points fall on the wrong structure.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

// A reference image of the pair as the verifier reads it.
struct VerifiedReference {
  cv::Mat gray8;                    // CV_8UC1
  std::vector<cv::Point2f> pixels;  // per map point: where it was measured (lens distortion kept)
  std::vector<char> distinctive;    // per map point: its corner here has no look-alike near it
};

struct PoseVerifierParams {
  int halfWindow = 5;     // n of the (2n+1)^2 windows compared
  double minScore = 0.7;  // warped NCC a frame corner needs to confirm a point
  double searchPx = 1.2;  // best score within this of the projection (at 320x240, scaled)
  int maxChecked = 100;   // points checked at most per frame (a random sample of the visible)
  int minConfirmed = 8;   // confirmed distinctive points needed (pose.verify_min_points)
  double minConfirmedShare = 0.2;  // ... and this share of the checkable ones (verify_min_share)
  // Short of that but with at least these, the pose is unsure rather than refuted
  // (pose.verify_unsure_points, verify_unsure_share): a second opinion may still accept it.
  int minUnsure = 4;
  double minUnsureShare = 0.12;
};

struct PoseCheck {
  enum class Verdict { Confirmed, Unsure, Refuted };
  Verdict verdict = Verdict::Confirmed;
  bool passed() const { return verdict == Verdict::Confirmed; }
  int checkable = 0;  // distinctive map points the pose projects into the frame
  int confirmed = 0;  // ... confirmed by a frame corner's warped correlation
  int reference = 0;  // 0: A, 1: B (the one nearer the frame's viewpoint)
  double ms = 0.0;
  std::string reason;  // why it was not confirmed
};

class PoseVerifier {
 public:
  // pointsA: the map points in reference A's camera frame; T_AB: A -> B; refs[0] = A, refs[1] = B.
  PoseVerifier(PinholeCamera camera, std::vector<Eigen::Vector3d> pointsA, const RigidPose& T_AB,
               VerifiedReference a, VerifiedReference b, PoseVerifierParams params);

  // gray8: the frame (CV_8UC1, the camera's size); T_Ak: reference A -> frame camera.
  PoseCheck check(const cv::Mat& gray8, const RigidPose& T_Ak) const;

  void setParams(const PoseVerifierParams& params) { params_ = params; }
  const PoseVerifierParams& params() const { return params_; }

 private:
  PinholeCamera camera_;
  std::vector<Eigen::Vector3d> pointsA_;
  RigidPose T_AB_;
  VerifiedReference refs_[2];
  std::vector<std::vector<int>> neighbours_[2];  // per reference, per point: nearest map points
  std::vector<int> order_;                       // the order points are checked in
  PoseVerifierParams params_;
};

}  // namespace reftrack
