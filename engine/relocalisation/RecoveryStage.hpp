#pragma once
// RecoveryStage: what stopped one way back to tracking (a start near a reference, or a
// relocalisation attempt) on a frame, or that it succeeded: the relocaliser's search stages
// (keypoints, matches with the map, PnP-RANSAC inliers, their share, their spread), the seeded
// pass of the pair tracker, the check of the pose by correlation, and the start rules
// (distinctive corners, keypoint support). Counted per attempt by `track` and `bench-real`.
#include <string>

namespace reftrack {

enum class RecoveryStage {
  None,                // not tried on this frame
  NotSearched,         // the recovery's budget was spent: nothing tried
  BlankFrame,          // black, covered or uniform: nothing to search
  TooFewKeypoints,     // relocaliser: too few keypoints in the frame
  TooFewMatches,       // relocaliser: ratio-test keypoint matches with a 3D point < min_inliers
  PnpInliers,          // relocaliser: PnP-RANSAC found no pose with min_inliers inliers
  InlierShare,         // relocaliser: the inliers are under min_inlier_ratio of the matches
  InlierSpread,        // relocaliser: inliers in too few grid cells or the pose too loosely fixed
  StartNoPose,         // start near a reference: its narrow-baseline matching gave no pose
  SeededPass,          // the pair tracker seeded with the pose found no supported pose
  Correlation,         // the check of the pose by correlation (PoseVerifier) refused it
  DistinctiveCorners,  // too few inliers on distinctive corners (min_distinctive_inliers)
  KeypointSupport,     // too few agreeing keypoint matches (min_keypoint_support, _agreement)
  Verified,            // the pose was verified and reported
};

// A short name for tables, e.g. "PnP inliers".
std::string toString(RecoveryStage stage);

}  // namespace reftrack
