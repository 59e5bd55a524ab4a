#pragma once
// UnpreparedMapParams (YAML section `unprepared`, `prepare --unprepared --params`): how a map is
// started from two views of an unprepared scene (no marker, no board, no given poses) — the
// keypoints matched between them, the essential matrix's RANSAC, the checks that refuse a pair
// which cannot fix a 3-D map (too few keypoints or matches, a pure rotation, too little
// parallax) and the gates of the first, pose-finding matching pass. Pixel figures are pixels of
// the references' own images.
#include <opencv2/core.hpp>
#include <string>

#include "engine/config/ParamSection.hpp"

namespace reftrack {

struct UnpreparedMapParams : ParamSection<UnpreparedMapParams> {
  static constexpr const char* kSection = "unprepared";

  // Keypoints of both views (KeypointFeatures: orb | akaze | sift), at most maxKeypoints each,
  // matched with Lowe's ratio test and a mutual check.
  std::string keypoints = "sift";
  int maxKeypoints = 4000;
  double ratio = 0.8;
  // A view with fewer keypoints than this is textureless; a pair with fewer matches than this
  // shares too little of the scene.
  int minKeypoints = 80;
  int minMatches = 60;
  // The essential matrix: five-point RANSAC (cv::findEssentialMat) on the undistorted keypoints,
  // a match an inlier within this distance of its epipolar line; at least minInliers of them.
  double ransacThresholdPx = 1.0;
  int minInliers = 40;
  // The pair must fix the translation: refused when a rotation alone (H = K R K^-1, the camera
  // turned on the spot) explains this share of the essential matrix's inliers within the same
  // threshold, and when the median angle between the two viewing rays of the inliers is below
  // minParallaxDeg (the preparation drops points under matching.min_parallax_deg, 1 deg).
  double maxRotationShare = 0.8;
  double minParallaxDeg = 1.5;
  // The first matching pass runs on the essential matrix's pose, before any refinement: its
  // epipolar and reprojection gates are wider than the preparation's.
  double bootstrapEpipolarDistancePx = 3.0;
  double bootstrapReprojectionErrorPx = 2.0;
  // Rounds of (corner matching, pose refinement from the matches) before the final preparation.
  int refinementRounds = 2;

  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
};
extern template struct ParamSection<UnpreparedMapParams>;  // defined in UnpreparedMapParams.cpp

}  // namespace reftrack
