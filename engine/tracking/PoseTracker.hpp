#pragma once
// PoseTracker (paper Sec. 3-6): the full 6-DOF tracker. Each frame: corners; while tracking,
// frame-to-frame narrow-baseline matching and homography, wide-baseline matching to V_A and V_B
// (WideBaselineMatcher), three-view pairs through the map's A<->B matches, outlier rejection by
// PnP-RANSAC on the 3D-2D pairs and an epipolar gate, the keypoint layer's points aligned around
// the robust pose's projections (KeypointMeasurer, wide_baseline.keypoint_points; the support is
// judged on the corners' terms, and the corners' own pose stands when the joint one fails it),
// then the pose x_Ak from the standard or the regularised estimator (TemporalRegularizer). Not
// tracking: initialisation by narrow-baseline matching to V_A (or V_B) and V_B through the stored
// matches, and when that finds too little, with the frame's windows resampled for one of a few
// distance ratios per frame (a start from farther away or nearer than the reference, along about
// its line of sight). Never reports a pose without enough inlier support (count, residual RMS,
// covariance and PoseSupport's reprojection SD, which rejects black, textureless and heavily
// blurred frames), nor one its check (PoseVerifier) refutes: the frame is `Lost` instead, with the
// reason. A pose that moved the scene farther than the wide-baseline search since the last frame (a
// jump), or that came from a seed's wide search, is matched once more around itself on the same
// frame, and that pass gives the frame's pose.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/config/TrackerParams.hpp"
#include "engine/estimation/CornerVarianceModel.hpp"
#include "engine/estimation/MotionModel.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/ReferenceMap.hpp"

namespace reftrack {

class RollingShutterEstimator;

enum class TrackingState { Initialising, Tracking, Lost };
const char* toString(TrackingState state);

// Limits of the 6-DOF tracker's sanity checks (defaults suit 320x240 to 1280x720).
struct PoseTrackerLimits {
  int minCorners = 20;                // fewer corners in a frame: textureless/black -> lost
  int minInliers = 15;                // fewer supporting matches -> lost
  double gatePx = 2.5;                // residual gate (pixels at 320x240, scaled with the image)
  double maxRmsPx = 1.5;              // three-view RMS at the solution (at 320x240, scaled) -> lost
  double maxSigmaTranslation = 0.05;  // metres: a larger pose SD means the estimate blew up
  // Support (PoseSupport.hpp): SD of the reprojected support points under the matches alone
  // (pixels at 320x240, scaled) above this -> lost.
  double maxSupportSdPx = 0.25;
  int ransacIterations = 100;         // PnP-RANSAC on the 3D-2D pairs
  double minEpipolarBaseline = 0.01;  // metres: closer to a reference, its epipolar terms drop
  void check() const;
};

struct StageTiming {
  std::string stage;
  double ms = 0.0;
};

struct PoseTrackingResult {
  TrackingState state = TrackingState::Initialising;
  std::string message;                     // how it initialised or why it is lost
  std::optional<RigidPose> worldToCamera;  // T_k = T_Ak T_A, only with support
  std::optional<RigidPose> T_Ak;
  Matrix6d covariance = Matrix6d::Zero();  // Omega_k of x_Ak
  double supportSdPx = 0.0;                // PoseSupport: reprojection SD from the matches alone
  double rollingShutterReadout = 0.0;      // the readout this frame was corrected with
  int corners = 0, matchesA = 0, matchesB = 0, threeView = 0, inliers = 0;
  int distinctiveInliers = 0;    // inliers on distinctive structure (DistinctiveCorners)
  int keypointMeasurements = 0;  // keypoint-layer terms added (wide_baseline.keypoint_points)
  // The check of the pose (PoseVerifier): distinctive map points it projects into the frame, and
  // how many of them the frame confirmed; verificationFailed: the frame is lost by that check.
  int verifyCheckable = 0, verifyConfirmed = 0;
  bool confirmedBySecondOpinion = false;  // the check fell short; the second opinion accepted it
  bool verificationFailed = false;
  std::vector<StageTiming> timings;
  double totalMs = 0.0;
  // The map points (camera A's frame) of the three-view inliers supportSdPx was measured on.
  std::vector<Eigen::Vector3d> supportPointsA;
  // Debug primitives in frame pixels: corners and inlier matches (frame pixel, reference pixel).
  std::vector<cv::Point2f> frameCorners;
  std::vector<std::pair<cv::Point2f, cv::Point2f>> inliersA, inliersB;
};

class PoseTracker {
 public:
  PoseTracker(ReferenceMap map, const TrackerParams& params, PoseTrackerLimits limits = {});
  ~PoseTracker();

  // One frame (BGR or grey, the map's image size; throws reftrack::Error on another size).
  PoseTrackingResult process(const cv::Mat& frame);

  void setParams(const TrackerParams& params);  // takes effect on the next frame
  void setMotionModel(const ArMotionModel& model);
  void setCornerVarianceModel(const CornerVarianceModel& model);
  // Back to initialising. What the tracker has learned of its map's points and corners
  // (pose.reliability_prior_observations) is kept: losing track says nothing about them.
  void reset();
  // Every map point, corner and kind of term back to the corner model.
  void forgetLearnedReliability();
  // The next process() starts from this world->camera pose instead of the previous frame (a
  // hand-over from another reference pair, or a relocalisation candidate): the reference corners'
  // 3D points projected with it seed the wide-baseline matching (H = identity, candidates within
  // wide_baseline.seed_search), then the usual outlier rejection, pose estimation and support
  // checks run, so a wrong seed ends Lost, never in a wrong pose. Resets the regulariser history.
  void seed(const RigidPose& worldToCamera);
  // The rolling-shutter readout in use (pose.rolling_shutter_readout, or its online estimate).
  double rollingShutterReadout() const;
  // A pose that its check (PoseVerifier) did not confirm, as a second opinion sees it.
  struct PoseInDoubt {
    RigidPose worldToCamera;
    bool unsure = false;     // the check was unsure (else it refuted the pose)
    bool trackedOn = false;  // tracked on from the last frame's pose (not a seed, not a jump)
  };
  // A second opinion on such a pose, given the frame: nullopt accepts it, else the reason to
  // refuse it. Without one such a pose is refused (MultiReferenceTracker asks its relocaliser).
  using PoseConfirmation =
      std::function<std::optional<std::string>(const cv::Mat& frame, const PoseInDoubt& pose)>;
  void setPoseConfirmation(PoseConfirmation confirmation);
  // More scene points for the check of every pose than the map's corner points: the references'
  // keypoints with a 3D point (world frame; pixels as detected in A, resp. B).
  struct VerificationKeypoint {
    Eigen::Vector3d world;
    cv::Point2f pixel;
  };
  void setVerificationKeypoints(std::vector<VerificationKeypoint> inA,
                                std::vector<VerificationKeypoint> inB);
  // Trackers of one camera share their readout estimate (MultiReferenceTracker's pair trackers).
  void shareRollingShutterEstimator(std::shared_ptr<RollingShutterEstimator> shared);
  const ReferenceMap& map() const;
  TrackingState state() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reftrack
