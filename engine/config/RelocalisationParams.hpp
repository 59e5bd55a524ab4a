#pragma once
// RelocalisationParams (YAML section `relocalisation`): the keypoint layer stored in the map and
// the cold start / relocalisation of the 6-DOF tracker from any view (issue 13). Keypoint counts
// are given at 640x480 and scale with the image area; pixel figures are given at 320x240 and
// scale with resolutionScale().
#include <opencv2/core.hpp>
#include <string>

namespace reftrack {

struct RelocalisationParams {
  bool enabled = true;              // false: start and re-start only near a reference (paper)
  std::string keypoints = "orb";    // detector + descriptor: orb | akaze | sift (measured choice)
  int featuresPerFrame = 1000;      // keypoints detected in a frame (640x480)
  int featuresPerReference = 2000;  // keypoints stored per reference (640x480)
  double ratio = 0.8;               // Lowe's ratio test on the two nearest descriptors
  int referencesToMatch = 4;        // retrieval: match only the best-voted references
  int ransacIterations = 300;       // PnP-RANSAC
  double reprojectionPx = 2.0;      // PnP-RANSAC inlier threshold (pixels at 320x240)
  int minInliers = 20;              // fewer inliers: no candidate (never a pose without support)
  double minInlierRatio = 0.25;     // inliers / 2D-3D matches below this: no candidate
  int attemptEveryFrames = 1;       // while lost, try on every n-th frame (time budget)
  // The inliers must cover at least this many cells of a 4x4 grid over the frame: a pose held
  // up by one small patch of the image is too weakly constrained to hand to the tracker.
  int minInlierCells = 3;
  // Keypoint layer (preparation): a keypoint gets a 3D point from a match with another view when
  // the match lies this close to its epipolar line and the triangulated point reprojects this
  // close in both views (pixels at 320x240), in front of both cameras, ...
  double triangulationPx = 1.0;
  // ... and the two rays meet at least at this angle (degrees): smaller parallax, no point.
  double minParallaxDeg = 1.0;

  // Keypoint counts for an image of `size` (the 640x480 figures scaled with the area).
  int featuresPerFrameFor(cv::Size size) const;
  int featuresPerReferenceFor(cv::Size size) const;

  void check() const;  // throws reftrack::Error naming the bad field (relocalisation.key)
  void write(cv::FileStorage& fs) const;
  void read(const cv::FileNode& node);  // missing keys keep their value
};

}  // namespace reftrack
