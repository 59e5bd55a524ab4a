#pragma once
// HomographyRefiner: the final, start-independent refinement of a registered homography. The
// reference, warped into the frame by the current H, is aligned to the frame at many textured
// reference points at once (pyramidal Lucas-Kanade, cv::calcOpticalFlowPyrLK: the residual
// displacement of each point), H is re-fitted to all those matches with a Cauchy-weighted
// Gauss-Newton (no threshold, no sampling: a continuous function of the matches), and the two
// steps repeat until H moves less than a hundredth of a pixel at the frame corners. Two
// registrations of one frame that start a few pixels apart (tracked in order, or cold through
// the keypoint layer) end at the same H: measured on the shared planar clips, up to 16 px apart
// at the frame corners before, at most 0.6 px after. A start within about a pixel (a tracked
// frame) skips the image pyramid and the whole-image warp: each round samples only the points'
// windows of the warped reference (WindowAlignment), which costs a fraction of warping the image.
// Images larger than 640x480 are aligned on a pyramid level that holds at least half its pixels
// (1280x720 and 1920x1080: the first), H carried there and back exactly.
#include <opencv2/core.hpp>
#include <vector>

#include "engine/features/ImagePyramid.hpp"
#include "engine/homography/SupportRegion.hpp"

namespace reftrack {

// How far the start may be from the truth: Coarse (a few pixels: a keypoint homography) runs the
// first round on a 3-level pyramid of the whole warped reference; Close (within about a pixel: a
// tracked frame's correlation fit) aligns the points' windows directly from the first round.
enum class RefineStart { Coarse, Close };

struct RefinedHomography {
  bool success = false;
  cv::Matx33d H = cv::Matx33d::eye();  // reference -> frame (the input H when !success)
  int points = 0;                      // reference points aligned in the last round
  int inliers = 0;                     // of those, within the Cauchy scale of the fit
  int rounds = 0;
  // The frame positions (the frame's pixels) of the last round's inliers.
  std::vector<cv::Point2f> inlierPoints;
};

class HomographyRefiner {
 public:
  // reference: 8-bit grey; pointsAt320x240: how many reference points (strongest Harris corners,
  // no grid quota, scaled with the image area). fullResolution: align on the given images
  // themselves whatever their size (a frame's pyramid level registered to the full reference).
  // Throws reftrack::Error on an empty reference or pointsAt320x240 < 8.
  HomographyRefiner(const cv::Mat& referenceGray, int pointsAt320x240, bool fullResolution = false);

  // frameGray: 8-bit grey; H: reference -> frame, within a few pixels of the truth where the
  // reference points land. Fails (success = false, H unchanged) when fewer than minInliers points
  // support the fit or the fit diverges. support: only the reference points H puts inside it
  // (frame pixels) are aligned — the part of a partly planar view that H explains (default: the
  // whole frame).
  RefinedHomography refine(const cv::Mat& frameGray, const cv::Matx33d& H, int minInliers,
                           RefineStart start = RefineStart::Coarse,
                           const SupportRegion& support = {}) const;
  // The same on the frame's pyramid (its level() is built once for every user of the pyramid).
  RefinedHomography refine(const ImagePyramid& frame, const cv::Matx33d& H, int minInliers,
                           RefineStart start = RefineStart::Coarse,
                           const SupportRegion& support = {}) const;

  const std::vector<cv::Point2f>& points() const { return points_; }  // full-resolution pixels
  int level() const { return level_; }  // the pyramid level aligned on (0: full resolution)

 private:
  RefinedHomography refineOnLevel(const cv::Mat& frameLevel, const cv::Matx33d& H, int minInliers,
                                  RefineStart start, const SupportRegion& support) const;

  int level_ = 0;
  cv::Mat reference_;                     // on the level
  std::vector<cv::Point2f> points_;       // full-resolution pixels
  std::vector<cv::Point2f> levelPoints_;  // the same on the level
};

}  // namespace reftrack
