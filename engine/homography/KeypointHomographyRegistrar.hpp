#pragma once
// KeypointHomographyRegistrar: a viewpoint-invariant first guess of the reference -> frame
// homography for cold registration — ORB / AKAZE / SIFT keypoints (the reference's detected once,
// also on synthetic tilted views of it, ASIFT-like), mutual nearest-neighbour descriptor matches
// passing Lowe's ratio test, and a RANSAC homography; failing a confident one, the mutual nearest
// neighbours alone (one-to-one, for repeated patterns) with MAGSAC++; failing any (ORB), the
// reference's keypoints detected densely, for frames zoomed far onto a part of it. It only
// predicts: HomographyTracker matches its correlation windows around this guess.
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <string>
#include <vector>

#include "engine/config/HomographyTrackerParams.hpp"
#include "engine/config/RansacParams.hpp"

namespace reftrack {

struct KeypointRegistration {
  bool found = false;
  cv::Matx33d H = cv::Matx33d::eye();  // reference -> frame (meaningful when found)
  int frameKeypoints = 0;
  int matches = 0;  // mutual, ratio-tested descriptor matches
  int inliers = 0;
  std::vector<cv::Point2f> inlierPoints;  // the inliers' positions in the frame (when found)
  std::string failure;                    // why found is false
};

class KeypointHomographyRegistrar {
 public:
  // reference: 8-bit grey or BGR. params.keypoints picks the detector (not None); ransac gives
  // the inlier count and determinant rules. Throws reftrack::Error on an empty reference, bad
  // parameters, the None layer, or a reference with fewer keypoints than ransac.minInliers.
  KeypointHomographyRegistrar(const cv::Mat& reference, const HomographyTrackerParams& params,
                              const RansacParams& ransac = {});

  // frame: 8-bit grey or BGR, any size (the inlier threshold scales with it). Throws
  // reftrack::Error on an empty frame.
  KeypointRegistration registerFrame(const cv::Mat& frame) const;

  int referenceKeypoints() const { return static_cast<int>(views_.front().keypoints.size()); }
  // 1 + homography.keypoint_tilt_views (+ 1 with ORB: the reference with finer levels, for
  // zoomed-in frames)
  int views() const { return static_cast<int>(views_.size()); }

 private:
  // The reference's keypoints (positions in the reference's pixels) and descriptors, detected
  // on the reference itself (views_[0]), on a synthetic tilted view of it, or (ORB, last) on
  // the reference with finer pyramid levels.
  struct View {
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
  };
  // Distinctive: mutual nearest neighbours passing the ratio test (keypoint_ratio), RANSAC.
  // OneToOne: mutual nearest neighbours alone, MAGSAC++ (cv::USAC_MAGSAC).
  enum class MatchPass { Distinctive, OneToOne };
  // Descriptor matching of the frame's keypoints to one view and its robust homography.
  // kept: the frame x view descriptor distances, computed here when empty and kept for the next
  // pass; nullptr: computed a block of frame rows at a time and dropped (a large view).
  KeypointRegistration registerToView(const View& view, const cv::Mat& gray,
                                      const std::vector<cv::KeyPoint>& keypoints,
                                      const cv::Mat& descriptors, MatchPass pass,
                                      cv::Mat* kept) const;
  // The last resort (ORB, nothing registered): the reference's keypoints detected densely
  // (made on first use), matched to the frame's detected at half its working scale.
  KeypointRegistration registerDense(const cv::Mat& gray) const;

  // Keypoints and descriptors of `gray`, detected at `scale` of its size (callers pass the image's
  // working scale: small images upsampled, large ones reduced; positions given in `gray`'s
  // pixels), the `features` strongest.
  void detect(const cv::Mat& gray, double scale, std::vector<cv::KeyPoint>& keypoints,
              cv::Mat& descriptors) const;

  HomographyTrackerParams params_;
  RansacParams ransac_;
  cv::Ptr<cv::Feature2D> detector_;
  int norm_ = cv::NORM_L2;
  std::vector<View> views_;
  cv::Mat referenceGray_;  // kept for the dense view (ORB only)
  // The dense view, made once on first use (registerFrame is const and may run on any thread).
  mutable std::unique_ptr<std::once_flag> denseOnce_ = std::make_unique<std::once_flag>();
  mutable View dense_;
};

}  // namespace reftrack
