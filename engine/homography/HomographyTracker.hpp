#pragma once
// HomographyTracker (paper Sec. 7.3, SPEC §5): registers each frame to a stored reference frame
// with one homography H (reference -> frame). While tracking, the frame is predicted from the
// previous result: the frame-to-frame homography (previous -> current, narrow-baseline matches
// + RANSAC) chained with the last reference -> previous one; reference corners are matched
// around their predicted positions with reference windows warped by the prediction (Eq. 19
// style), solved robustly and refined; failing that, the denser re-acquisition corners are
// matched around the same prediction. A frame with too few inliers among the reference corners
// that fall inside it (and whose window can be formed) is flagged lost. The next frames are
// still matched guided by the last prediction carried on with frame-to-frame homographies
// (coasting); when that fails too, or no frame-to-frame homography is found, a frame is matched
// cold: first by the keypoint layer (homography.keypoints: descriptor matches give a homography
// from any viewpoint, around which the reference corners are matched with warped windows as
// above, so the result has the correlation's precision and passes the same inlier rules), then,
// failing that, unguided (square windows, whole image, a denser corner set on both sides, RANSAC
// drawing from the best correlation scores first; a hypothesis short of the inlier rules is
// re-matched around its own prediction), so tracking re-acquires on its own when the view
// returns. Every registered H is finally refined (HomographyRefiner, homography.refine_points),
// so a frame gets the same H whether it was tracked or registered cold. A registration not
// carried from the previous frame's (cold, or after a loss) is reported only once
// RegistrationVerifier confirms it (homography.verify): the reference warped by H must match the
// frame over the region its inlier matches span (a view may be only partly the plane), which
// must hold verify_min_support of the overlap; otherwise the frame is lost with the reason. A cold
// frame that magnifies the reference (a 2-4x zoom) is registered on the pyramid level where the
// reference appears at about its own scale. Reference and frames may differ in size (another
// camera). Given the camera's K, a frame the general homography fails on — or fits on a thin strip
// only — is solved with the rotation-only model H = K R K^-1 (homography.rotation_model), which a
// sliver of overlap still determines.
#include <Eigen/Core>
#include <map>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/config/TrackerParams.hpp"
#include "engine/features/Corner.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/homography/HomographyRefiner.hpp"
#include "engine/homography/KeypointHomographyRegistrar.hpp"
#include "engine/homography/RegistrationVerifier.hpp"
#include "engine/homography/RobustHomographyEstimator.hpp"
#include "engine/homography/RotationHomographyEstimator.hpp"
#include "engine/matching/NarrowBaselineMatcher.hpp"
#include "engine/matching/NccCorrelation.hpp"

namespace reftrack {

struct HomographyTrackResult {
  bool tracked = false;
  cv::Matx33d H = cv::Matx33d::eye();  // reference -> this frame (meaningful when tracked)
  double inlierRatio = 0.0;            // inliers / reference corners mapped inside this frame
  int corners = 0;                     // corners detected in this frame
  int matches = 0;                     // correlation matches to the reference
  int inliers = 0;
  bool guided = false;  // matched around a prediction from earlier frames (false: cold)
  // Cold registration through the keypoint layer: the correlation matching was guided by the
  // keypoint homography (guided stays false).
  bool keypointGuided = false;
  bool rotationModel = false;  // H is the rotation-only model K R K^-1 (needs K)
  std::string failure;         // why the frame was not tracked
  // What the registration check compared and found (RegistrationCheck::summary), when it ran
  // on this frame (cold registrations, jumps), passed or not.
  std::string check;
  std::vector<cv::Point2f> frameCorners;  // corner positions detected in this frame
  // Inlier correspondences (reference position, frame position) of the final H.
  std::vector<std::pair<cv::Point2f, cv::Point2f>> inlierMatches;
  // Milliseconds per stage, in order: corners, prediction, matching, robust fit, keypoints,
  // refine, verify.
  std::vector<std::pair<std::string, double>> stageMs;
};

class HomographyTracker {
 public:
  // reference: the stored frame (8-bit grey or BGR), of any size; K: the intrinsics of the
  // frames' camera when calibrated. It enables the rotation-only model for frames of the
  // reference's size (the reference is then taken to come from the same camera; of another size,
  // it comes from another camera whose K is unknown, and only the general homography is fitted).
  // Throws reftrack::Error on an empty image, bad parameters, a non-invertible K, or a reference
  // with fewer than 8 corners.
  HomographyTracker(const cv::Mat& reference, const TrackerParams& params,
                    const std::optional<Eigen::Matrix3d>& K = std::nullopt);

  // Frames may have any size (another camera than the reference's); a frame whose size differs
  // from the previous one's is registered cold. Throws reftrack::Error on an empty frame.
  HomographyTrackResult track(const cv::Mat& frame);
  void reset();  // forget the previous frame: the next one is matched unguided

  const std::vector<Corner>& referenceCorners() const { return ref_.corners; }
  cv::Size referenceSize() const { return refGray_.size(); }
  bool lost() const { return !lastH_.has_value(); }

 private:
  // base (reference -> previous frame) chained with the frame-to-frame homography previous ->
  // this frame; base alone when that is switched off or fails, nullopt when it fails while
  // coasting.
  std::optional<cv::Matx33d> predict(const cv::Matx33d& base, bool coasting,
                                     const std::vector<cv::Point2f>& points,
                                     const NccPatches& patches, cv::Size frameSize) const;

  // corners, prediction, matching, robust fit, keypoints, refine, verify
  static constexpr int kStages = 7;

  // One corner set of the reference with its windows (tracking or re-acquisition density).
  struct ReferenceSet {
    std::vector<Corner> corners;
    std::vector<cv::Point2f> points;
    NccPatches patches;
  };
  static ReferenceSet referenceSet(const cv::Mat& gray, const CornerDetector& detector,
                                   int halfWindow);

  // One registration attempt of a frame: guided by the prediction from `base` when there is
  // one (base chained with the frame-to-frame homography, or base itself when
  // chainFrameToFrame is false), else unguided. stageMs accumulates corners, prediction,
  // matching, robust fit (stageMs[0..3]).
  struct Attempt {
    std::vector<cv::Point2f> points;  // the frame's corners
    NccPatches patches{1};
    std::optional<cv::Matx33d> prediction;
    int matches = 0;
    std::vector<cv::Point2f> src, dst;  // matched reference / frame positions
    HomographyEstimate est;
    double inlierRatio = 0.0;
    bool rotationModel = false;
    // The best H either model found, even when it fails the inlier rules.
    std::optional<cv::Matx33d> hypothesis;
    bool tracked = false;
    std::string failure;
    // Registered on this frame pyramid level (then refined there; H, points and dst carried
    // back to full resolution).
    int level = 0;
    bool finished = false;  // refined and checked (finish())
    // The whole-image alignment's inliers (full-resolution frame pixels) when H is that
    // alignment's (the corner matches failed): the support region then.
    std::vector<cv::Point2f> alignedInliers;
    std::string check;  // the registration check's summary, when it ran
  };
  // support: the frame region the guide is known to explain (a keypoint homography's inliers):
  // the inlier ratio counts only the reference corners it puts there.
  Attempt attempt(const ImagePyramid& frame, const CornerDetector& detector,
                  const ReferenceSet& ref, const std::optional<cv::Matx33d>& base, bool coasting,
                  double stageMs[kStages], bool chainFrameToFrame = true, int denseRadius = 0,
                  const SupportRegion& support = {});
  // Matches the attempt's frame corners to `ref` — around the positions `guide` predicts
  // (warped windows, +-guidedHalf pixels), or unguided — then fits H (the general model, then
  // the rotation model) and applies the inlier rules. stageMs[2..3] accumulate. denseRadius > 0:
  // guided, each warped window is searched at every pixel within +-denseRadius of its predicted
  // position instead of at the frame's corners (searchWarpedWindows).
  void matchAndFit(Attempt& a, const cv::Mat& gray, const ReferenceSet& ref,
                   const std::optional<cv::Matx33d>& guide, double guidedHalf,
                   double stageMs[kStages], int denseRadius = 0,
                   const SupportRegion& support = {}) const;
  // The region of the frame (full resolution) the attempt's H is known to explain: the convex
  // hull of its inliers' frame positions (or of the alignment's), with supportMargin.
  SupportRegion supportOf(const Attempt& a, cv::Size frameSize) const;
  // The registered attempt's H refined by `refiner` (refiner_ when null; kept when it still fits
  // the attempt's inliers); stageMs[5] accumulates.
  void refine(Attempt& a, const ImagePyramid& frame, double stageMs[kStages],
              const HomographyRefiner* refiner = nullptr, const SupportRegion& support = {}) const;
  // A registration not carried from the previous frame's (cold, or after a loss): refined
  // (unless done on a pyramid level, or the rotation model) and checked by verifier_; a refused
  // one is no longer tracked and says why. stageMs[5..6] accumulate.
  void finish(Attempt& a, const ImagePyramid& frame, double stageMs[kStages]) const;
  // Registration around `start` (reference -> frame, a few pixels off): aligned by the refiner,
  // then the reference windows searched close around it (on a pyramid level for a frame that
  // magnifies the reference), finished.
  // startInliers: the frame positions (full resolution) of the matches that gave start (a
  // keypoint homography's inliers; empty: the whole frame).
  Attempt alignedAttempt(const ImagePyramid& frame, const cv::Matx33d& start,
                         double stageMs[kStages],
                         const std::vector<cv::Point2f>& startInliers = {});
  // Registration without a prediction: around the keypoint layer's homography, then unguided;
  // each finished.
  Attempt coldAttempt(const ImagePyramid& frame, double stageMs[kStages], bool& keypointGuided);

  TrackerParams params_;
  CornerDetector detector_;                // the reference's tracking corners
  CornerDetector frameDetector_;           // a tracked frame's: count times frame_corner_factor
  CornerDetector reacquireDetector_;       // the reference's while lost: count times
                                           // reacquire_corner_factor
  CornerDetector frameReacquireDetector_;  // the same for the frames' size
  cv::Size frameSize_;                     // of the last frame
  NarrowBaselineMatcher matcher_;
  RobustHomographyEstimator estimator_;
  std::optional<RotationHomographyEstimator> rotationEstimator_;  // with K and rotation_model
  std::optional<KeypointHomographyRegistrar> keypointRegistrar_;  // unless keypoints is none
  std::optional<HomographyRefiner> refiner_;                      // unless refine_points is 0
  // Cold registrations on frame pyramid level l > 0 (a zoomed frame sees a 4^-l part of the
  // reference): refiners aligning the full reference to the level with 4^l times the points,
  // built on first use (key l).
  std::map<int, HomographyRefiner> levelRefiners_;
  const HomographyRefiner& levelRefiner(int level);
  std::optional<RegistrationVerifier> verifier_;  // unless verify is false
  cv::Mat refGray_;
  ReferenceSet ref_, reacquireRef_;
  // The previous frame (for the frame-to-frame homography) and its registration.
  std::optional<cv::Matx33d> lastH_;
  // After a loss: the last prediction carried on by frame-to-frame homographies, so the next
  // frames are still matched guided (dropped when a frame-to-frame homography fails).
  std::optional<cv::Matx33d> coastH_;
  std::vector<cv::Point2f> prevPoints_;
  NccPatches prevPatches_;
};

// Rotation-only pose for a camera that only rotates: H = K R K^-1 gives R = K^-1 H K, scaled to
// unit determinant and projected onto SO(3). R maps reference-camera coordinates to the
// current camera's (X_cur = R X_ref).
Eigen::Matrix3d rotationFromHomography(const cv::Matx33d& H, const Eigen::Matrix3d& K);

}  // namespace reftrack
