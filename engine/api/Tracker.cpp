#include "engine/api/Tracker.hpp"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <chrono>
#include <opencv2/imgcodecs.hpp>

#include "engine/config/TrackerParams.hpp"
#include "engine/core/Error.hpp"
#include "engine/core/ThreadCpuClock.hpp"
#include "engine/estimation/MotionModelFile.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/homography/HomographyTracker.hpp"
#include "engine/reference/MultiReferenceMap.hpp"
#include "engine/tracking/MultiReferenceTracker.hpp"

namespace reftrack {

namespace {

// x_k = vec6(T(x_Ak) * T_A): the world -> camera 6-vector as a function of the tracker's x_Ak,
// differentiated by Ceres (Jets) to carry Omega_k over to the world frame.
struct WorldPoseFromRelative {
  Eigen::Matrix3d RA;
  Eigen::Vector3d tA;
  template <typename T>
  bool operator()(const T* x, T* out) const {
    T R[9];
    ceres::AngleAxisToRotationMatrix(x + 3, ceres::RowMajorAdapter3x3(R));
    T Rk[9];
    for (int i = 0; i < 3; ++i) {
      out[i] = x[i];
      for (int j = 0; j < 3; ++j) {
        Rk[3 * i + j] = T(0);
        for (int m = 0; m < 3; ++m) Rk[3 * i + j] += R[3 * i + m] * RA(m, j);
        out[i] += R[3 * i + j] * tA(j);
      }
    }
    ceres::RotationMatrixToAngleAxis(ceres::RowMajorAdapter3x3(static_cast<const T*>(Rk)), out + 3);
    return true;
  }
};

// Omega_k of x_Ak -> covariance of the world -> camera 6-vector, to first order: J Omega J^T.
Matrix6d worldCovariance(const Matrix6d& omegaAk, const RigidPose& T_Ak, const RigidPose& T_A) {
  ceres::AutoDiffCostFunction<WorldPoseFromRelative, 6, 6> f(
      new WorldPoseFromRelative{T_A.rotation(), T_A.translation()});
  const Vector6d x = T_Ak.toVector6();
  const double* parameters[] = {x.data()};
  double value[6];
  Eigen::Matrix<double, 6, 6, Eigen::RowMajor> J;
  double* jacobians[] = {J.data()};
  if (!f.Evaluate(parameters, value, jacobians))
    throw Error("tracker: cannot propagate the pose covariance");
  const Matrix6d cov = J * omegaAk * J.transpose();
  return 0.5 * (cov + cov.transpose());
}

TrackerParams loadParams(const TrackerOptions& options, TrackingMode mode) {
  TrackerParams params =
      options.params.empty() ? TrackerParams{} : TrackerParams::load(options.params);
  if (!options.motionModel.empty()) params.pose.motionModelFile = options.motionModel.string();
  params.mode = mode;
  return params;
}

}  // namespace

const char* toString(Tracker::State state) {
  switch (state) {
    case Tracker::State::Initialising:
      return "initialising";
    case Tracker::State::Tracking:
      return "tracking";
    case Tracker::State::Lost:
      return "lost";
    case Tracker::State::Uncertain:
      return "uncertain";
  }
  return "unknown";
}

struct Tracker::Impl {
  Mode mode = Mode::SixDof;
  cv::Size size;           // the frames' required size (empty: any)
  cv::Size referenceSize;  // the map's, or the reference image's
  std::optional<Eigen::Matrix3d> K;
  std::unique_ptr<MultiReferenceTracker> sixDof;
  std::unique_ptr<HomographyTracker> homography;
  int frames = 0;
  bool trackedSinceReset = false;  // homography mode: a failure is Lost, not Initialising

  void trackSixDof(const cv::Mat& frame, Result& out) {
    const MultiReferenceResult r = sixDof->process(frame);
    const PoseTrackingResult& p = r.tracking;
    out.state = p.state == TrackingState::Tracking ? State::Tracking
                : p.state == TrackingState::Lost   ? State::Lost
                                                   : State::Initialising;
    out.reason = p.message;
    if (out.state == State::Tracking && r.uncertain) {
      out.state = State::Uncertain;
      out.reason = r.uncertainReason;
    }
    if (!r.notice.empty()) out.reason += (out.reason.empty() ? "" : "; ") + r.notice;
    out.inliers = p.inliers;
    out.referenceA = r.referenceA;
    out.referenceB = r.referenceB;
    out.relocalised = r.relocalisation.succeeded;
    if (p.state == TrackingState::Tracking && p.worldToCamera) {
      out.worldToCamera = p.worldToCamera;
      out.predictedErrorPx = r.predictedErrorPx;
      if (p.T_Ak) {
        const RigidPose T_A = p.T_Ak->inverse() * *p.worldToCamera;
        out.covariance = worldCovariance(p.covariance, *p.T_Ak, T_A);
      }
    }
  }

  void trackHomography(const cv::Mat& frame, Result& out) {
    const HomographyTrackResult r = homography->track(frame);
    out.inliers = r.inliers;
    if (r.tracked) {
      trackedSinceReset = true;
      out.state = State::Tracking;
      out.homography = r.H;
      if (r.rotationModel) out.reason = "rotation-only model";
      // K is the frames' camera: the rotation pose needs a reference from the same camera.
      if (K && frame.size() == referenceSize)
        out.worldToCamera = RigidPose(rotationFromHomography(r.H, *K), Eigen::Vector3d::Zero());
    } else {
      out.state = trackedSinceReset ? State::Lost : State::Initialising;
      out.reason = r.failure;
    }
  }
};

Tracker::Tracker(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Tracker::Tracker(Tracker&&) noexcept = default;
Tracker& Tracker::operator=(Tracker&&) noexcept = default;
Tracker::~Tracker() = default;

Tracker Tracker::openMap(const std::filesystem::path& mapFolder, const TrackerOptions& options) {
  return openMap(mapFolder, loadParams(options, TrackingMode::SixDof));
}

Tracker Tracker::openMap(const std::filesystem::path& mapFolder, const TrackerParams& params) {
  TrackerParams p = params;
  p.mode = TrackingMode::SixDof;
  p.check();
  // The pair trackers load the motion model on first use: a bad file is reported here instead.
  if (!p.pose.motionModelFile.empty()) (void)loadMotionModel(p.pose.motionModelFile);
  MultiReferenceMap map = MultiReferenceMap::load(mapFolder);
  auto impl = std::make_unique<Impl>();
  impl->mode = Mode::SixDof;
  impl->size = map.camera.imageSize();
  impl->referenceSize = impl->size;
  impl->K = map.camera.K();
  impl->sixDof = std::make_unique<MultiReferenceTracker>(std::move(map), p);
  return Tracker(std::move(impl));
}

Tracker Tracker::openReference(const std::filesystem::path& referenceImage,
                               const std::filesystem::path& cameraFile,
                               const TrackerOptions& options) {
  return openReference(referenceImage, cameraFile, loadParams(options, TrackingMode::Homography));
}

Tracker Tracker::openReference(const std::filesystem::path& referenceImage,
                               const std::filesystem::path& cameraFile,
                               const TrackerParams& params) {
  if (!std::filesystem::is_regular_file(referenceImage))
    throw Error("reference image '" + referenceImage.string() + "' does not exist");
  const cv::Mat reference = cv::imread(referenceImage.string(), cv::IMREAD_COLOR);
  if (reference.empty())
    throw Error("cannot read the reference image '" + referenceImage.string() + "'");
  std::optional<PinholeCamera> camera;
  if (!cameraFile.empty()) camera = PinholeCamera::load(cameraFile);
  Tracker t = openReference(
      reference, camera ? std::optional<Eigen::Matrix3d>(camera->K()) : std::nullopt, params);
  if (camera) t.impl_->size = camera->imageSize();  // the frames' camera fixes their size
  return t;
}

Tracker Tracker::openReference(const cv::Mat& reference, const std::optional<Eigen::Matrix3d>& K,
                               const TrackerParams& params) {
  TrackerParams p = params;
  p.mode = TrackingMode::Homography;
  p.check();
  auto impl = std::make_unique<Impl>();
  impl->mode = Mode::Homography;
  impl->K = K;
  impl->homography = std::make_unique<HomographyTracker>(reference, p, K);
  impl->referenceSize = impl->homography->referenceSize();
  return Tracker(std::move(impl));
}

Tracker::Result Tracker::track(const cv::Mat& frame) {
  const auto start = std::chrono::steady_clock::now();
  if (frame.empty()) throw Error("tracker: empty frame");
  if (impl_->size.area() > 0 && frame.size() != impl_->size)
    throw Error("tracker: frame is " + std::to_string(frame.cols) + "x" +
                std::to_string(frame.rows) + " but the " +
                (impl_->mode == Mode::SixDof ? "map" : "camera") + " is " +
                std::to_string(impl_->size.width) + "x" + std::to_string(impl_->size.height));
  Result out;
  out.frameIndex = impl_->frames++;
  if (impl_->mode == Mode::SixDof)
    impl_->trackSixDof(frame, out);
  else
    impl_->trackHomography(frame, out);
  out.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

void Tracker::reset() {
  impl_->frames = 0;
  impl_->trackedSinceReset = false;
  if (impl_->sixDof) impl_->sixDof->reset();
  if (impl_->homography) impl_->homography->reset();
}

void Tracker::setOverlayPoints(const std::vector<Eigen::Vector3d>& worldPoints) {
  if (!impl_->sixDof) throw Error("tracker: overlay points apply to 6-DOF tracking (a map)");
  impl_->sixDof->setOverlayPoints(worldPoints);
}

void Tracker::setRealTimeBudget(bool on) {
  if (impl_->sixDof)
    impl_->sixDof->setBudgetClock(on ? std::function<double()>(processCpuMs)
                                     : std::function<double()>());
}

Tracker::Mode Tracker::mode() const { return impl_->mode; }
cv::Size Tracker::imageSize() const { return impl_->size; }
cv::Size Tracker::referenceSize() const { return impl_->referenceSize; }
std::optional<Eigen::Matrix3d> Tracker::camera() const { return impl_->K; }

}  // namespace reftrack
