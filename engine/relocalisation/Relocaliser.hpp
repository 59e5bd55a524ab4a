#pragma once
// Relocaliser (issue 13): cold start and relocalisation from any view in the mapped volume.
// Matches the frame's viewpoint-invariant keypoints to the references' stored keypoint layers
// (a retrieval step picks the references to match when there are many), PnP-RANSAC on their 3D
// points, then a least-squares refinement on the inliers. Returns a candidate pose only with
// enough inlier support; the 6-DOF tracker then refines and verifies it with the paper's warped
// correlation (PoseTracker::seed) before reporting it. locate() is const and thread-compatible.
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/config/RelocalisationParams.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/MultiReferenceMap.hpp"
#include "engine/relocalisation/RecoveryStage.hpp"
#include "engine/relocalisation/RecoveryWork.hpp"
#include "engine/relocalisation/ReferenceKeypointBuilder.hpp"  // buildReferenceKeypoints

namespace reftrack {

struct RelocalisationCandidate {
  RigidPose worldToCamera;
  int reference = -1;  // the reference with the most inlier matches
  int inliers = 0;
  int matches = 0;
  double reprojectionRmsPx = 0.0;
  // The inliers among the ratio-test matches (before the guided matching): keypoints whose
  // descriptor has no look-alike in the references, with their 3D points (world) and their pixels
  // in the frame (as detected, lens distortion included).
  std::vector<cv::Point3f> distinctivePoints;
  std::vector<cv::Point2f> distinctivePixels;
};

struct KeypointSupport {
  int matches = 0;    // frame keypoints with a ratio-test match to a keypoint with a 3D point
  int agreeing = 0;   // ... whose 3D point the pose projects within the inlier threshold
  KeypointWork work;  // what finding them did, counted (the recovery's cost model)
};

struct RelocalisationAttempt {
  std::optional<RelocalisationCandidate> candidate;  // nullopt: no pose with enough support
  std::string message;                               // why not, or what was found
  // The search stage that stopped it (TooFewKeypoints .. InlierSpread); None with a candidate.
  RecoveryStage stop = RecoveryStage::None;
  double ms = 0.0;     // wall time of locate()
  double cpuMs = 0.0;  // the process's CPU time of locate() (OpenCV's worker threads included)
  KeypointWork work;   // what locate() did, counted: the same for the same frame on any machine
};

class Relocaliser {
 public:
  // Uses the map's stored keypoint layers (throws reftrack::Error when they are missing or were
  // made with another detector than params.keypoints).
  Relocaliser(const MultiReferenceMap& map, const RelocalisationParams& params);
  ~Relocaliser();
  // BGR or grey, the map's size (else reftrack::Error); a frame without enough support (black,
  // textureless, another scene) gives no candidate and says why in the message. `fullResolution`:
  // SIFT detects on the whole frame, not reduced by sift_frame_scale (slower, the precision of a
  // full-size detection: for a second opinion on an unsure pose).
  RelocalisationAttempt locate(const cv::Mat& frame, bool fullResolution = false) const;
  // Support for a pose found otherwise (a start near a reference): the frame's keypoints'
  // ratio-test matches to every reference's layer, and how many of them `worldToCamera` projects
  // within the PnP inlier threshold. Such matches have no look-alike in the references, so a pose
  // one period off on repeated texture gets few. Same frame contract as locate().
  KeypointSupport ratioTestSupport(const cv::Mat& frame, const RigidPose& worldToCamera) const;
  // How many of the 3D points (world) `worldToCamera` projects (lens distortion included)
  // within the PnP inlier threshold (times thresholdScale) of their pixels (as detected): e.g. a
  // candidate's distinctive inliers under a refined pose.
  int agreeing(const RigidPose& worldToCamera, const std::vector<cv::Point3f>& points,
               const std::vector<cv::Point2f>& pixels, double thresholdScale = 1.0) const;
  const PinholeCamera& camera() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reftrack
