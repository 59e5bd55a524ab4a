#pragma once
// reftrack::Tracker — the stable entry point for a program that only wants poses. Open it on a
// map folder written by `reftrack prepare` (6-DOF: the paper's two-reference tracker on the best
// pair of the map's N references, relocalising after a loss) or on one reference image
// (homography mode, paper Sec. 3.2), then call track() once per frame, in order. Frames are 8-bit
// BGR or grey of the map's (reference's) image size. Every failure — a missing or bad map, image,
// camera or parameter file, a frame of another size — throws reftrack::Error with the reason.
// Poses follow SPEC.md: world -> camera, X_camera = R * X_world + t, world = the marker's frame.
#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

struct TrackerParams;

struct TrackerOptions {
  std::filesystem::path params;       // TrackerParams YAML (`--params`); empty = defaults
  std::filesystem::path motionModel;  // fitted motion model (`fit-motion --out`); empty = none
};

class Tracker {
 public:
  enum class Mode { SixDof, Homography };
  // Initialising: no pose since open/reset. Uncertain (6-DOF): tracked, but the overlay error the
  // covariance predicts exceeds pose.max_predicted_error_px — the pose and covariance are given
  // (the tracker goes on from them) but should not be drawn as if exact; `reason` says why.
  enum class State { Initialising, Tracking, Lost, Uncertain };

  struct Result {
    State state = State::Initialising;
    std::string reason;   // why not tracking; while tracking, how the pose was found, if notable
    int frameIndex = -1;  // 0 for the first track() call after open or reset()
    // 6-DOF, set while tracking. Homography mode with a camera and a reference of its size: the
    // rotation-only pose of a camera turning about its centre (world = the reference camera's
    // frame, t = 0).
    std::optional<RigidPose> worldToCamera;
    // 6-DOF: covariance of worldToCamera's 6-vector (t_x, t_y, t_z, r_x, r_y, r_z), r axis-angle
    // (metres, radians): the tracker's Omega_k (paper Sec. 5) propagated to the world frame. It
    // counts the frame's corner noise, not the map's: on an exact synthetic scene the errors were
    // 2.3 times the predicted SDs (RMS; tests/engine/api/Tracker_test.cpp), on real clips over 10
    // times: predictedErrorPx rescales it by the frame's observed residuals and a calibration.
    std::optional<Eigen::Matrix<double, 6, 6>> covariance;
    // 6-DOF, with a pose: the overlay error in pixels the pose covariance predicts for the
    // overlay's points (setOverlayPoints): the RMS over them of the expected image displacement,
    // rescaled by the frame's observed residuals and times pose.predicted_error_scale
    // (engine/tracking/PredictedOverlayError.hpp); on the real desk and shelf clips the median of
    // true / predicted cube error is 1.0 and 1.25.
    std::optional<double> predictedErrorPx;
    std::optional<cv::Matx33d> homography;  // homography mode: reference pixel -> frame pixel
    int inliers = 0;                        // matches supporting the result
    int referenceA = -1, referenceB = -1;   // 6-DOF: the pair of references in use (-1: none)
    bool relocalised = false;               // 6-DOF: this pose came from the relocaliser
    double milliseconds = 0.0;              // time spent in track()
  };

  // 6-DOF tracking against a prepared map (format 2, or a version-1 two-reference map).
  static Tracker openMap(const std::filesystem::path& mapFolder, const TrackerOptions& = {});
  static Tracker openMap(const std::filesystem::path& mapFolder, const TrackerParams& params);
  // Homography mode against one stored frame of any size; cameraFile (camera.yml, optional) is
  // the frames' camera: the frames must have its size, and a reference of that size is taken to
  // come from the same camera (the rotation-only model and pose apply); a reference of another
  // size is a picture from another camera (general homography only, no pose). K: the same, as a
  // matrix (no size check).
  static Tracker openReference(const std::filesystem::path& referenceImage,
                               const std::filesystem::path& cameraFile = {},
                               const TrackerOptions& = {});
  static Tracker openReference(const std::filesystem::path& referenceImage,
                               const std::filesystem::path& cameraFile,
                               const TrackerParams& params);
  static Tracker openReference(const cv::Mat& reference, const std::optional<Eigen::Matrix3d>& K,
                               const TrackerParams& params);

  Tracker(Tracker&&) noexcept;
  Tracker& operator=(Tracker&&) noexcept;
  ~Tracker();

  Result track(const cv::Mat& frame);
  void reset();  // forget the past: the next frame is tracked as a first one (frameIndex 0)
  // 6-DOF: the object whose overlay error predictedErrorPx predicts, as points in the world frame
  // (e.g. the 8 vertices of the drawn cube); empty: the corners of the box holding the central
  // part of the map's points (the default). Throws reftrack::Error in homography mode or for a
  // point that is not finite.
  void setOverlayPoints(const std::vector<Eigen::Vector3d>& worldPoints);
  // 6-DOF: how the search after a loss is budgeted (relocalisation.budget_*). Off (the default):
  // in the modelled cost of its work, so the same frames give the same poses on any machine and
  // under any load (recorded input). On: in the CPU time it takes (a live camera, where the
  // budget must bound the real cost; results then depend on the machine's load). No effect in
  // homography mode.
  void setRealTimeBudget(bool on);

  Mode mode() const;
  // The frame size track() accepts: the map's (6-DOF), the camera's (homography mode with a
  // camera file); empty when any size is accepted (homography mode otherwise).
  cv::Size imageSize() const;
  cv::Size referenceSize() const;  // homography mode: the reference image's; 6-DOF: the map's
  std::optional<Eigen::Matrix3d> camera() const;  // K, when known

 private:
  struct Impl;
  explicit Tracker(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// "initialising", "tracking", "lost", "uncertain"
const char* toString(Tracker::State state);

}  // namespace reftrack
