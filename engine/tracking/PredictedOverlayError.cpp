#include "engine/tracking/PredictedOverlayError.hpp"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

// Pixel of a fixed point as a function of the pose 6-vector (t, r): K (R(r) X + t), dehomogenised.
struct PointProjection {
  Eigen::Matrix3d K;
  Eigen::Vector3d X;
  template <typename T>
  bool operator()(const T* pose, T* pixel) const {
    const T point[3] = {T(X.x()), T(X.y()), T(X.z())};
    T camera[3];
    ceres::AngleAxisRotatePoint(pose + 3, point, camera);
    for (int i = 0; i < 3; ++i) camera[i] += pose[i];
    const T u = T(K(0, 0)) * camera[0] + T(K(0, 1)) * camera[1] + T(K(0, 2)) * camera[2];
    const T v = T(K(1, 1)) * camera[1] + T(K(1, 2)) * camera[2];
    pixel[0] = u / camera[2];
    pixel[1] = v / camera[2];
    return true;
  }
};

double percentile(std::vector<double> values, double q) {
  const auto k = static_cast<std::size_t>(std::lround(q * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + static_cast<long>(k), values.end());
  return values[k];
}

}  // namespace

Eigen::Matrix<double, 2, 6> projectionJacobian(const PinholeCamera& camera, const RigidPose& pose,
                                               const Eigen::Vector3d& point) {
  ceres::AutoDiffCostFunction<PointProjection, 2, 6> projection(
      new PointProjection{camera.K(), point});
  const Vector6d x = pose.toVector6();
  const double* parameters[] = {x.data()};
  double pixel[2];
  Eigen::Matrix<double, 2, 6, Eigen::RowMajor> J;
  double* jacobians[] = {J.data()};
  if (!projection.Evaluate(parameters, pixel, jacobians) || !J.allFinite())
    throw Error("predicted overlay error: cannot differentiate the projection of a point");
  return J;
}

std::optional<double> predictedOverlayErrorPx(const PinholeCamera& camera, const RigidPose& pose,
                                              const Matrix6d& covariance,
                                              const std::vector<Eigen::Vector3d>& points) {
  if (!covariance.allFinite())
    throw Error("predicted overlay error: the pose covariance is not finite");
  double sumTrace = 0.0;
  int inFront = 0;
  for (const Eigen::Vector3d& X : points) {
    if (!((pose * X).z() > 0)) continue;  // behind the camera: not drawn
    const Eigen::Matrix<double, 2, 6> J = projectionJacobian(camera, pose, X);
    sumTrace += (J * covariance * J.transpose()).trace();
    ++inFront;
  }
  if (inFront == 0) return std::nullopt;
  return std::sqrt(std::max(0.0, sumTrace / inFront));
}

std::optional<double> overlayErrorPx(const PinholeCamera& camera, const RigidPose& truth,
                                     const RigidPose& estimate,
                                     const std::vector<Eigen::Vector3d>& worldPoints) {
  double sum = 0.0;
  int inFront = 0;
  for (const Eigen::Vector3d& X : worldPoints) {
    const Eigen::Vector3d a = truth * X, b = estimate * X;
    if (!(a.z() > 0) || !(b.z() > 0)) continue;
    sum += (camera.project(a) - camera.project(b)).norm();
    ++inFront;
  }
  if (inFront == 0) return std::nullopt;
  return sum / inFront;
}

std::vector<Eigen::Vector3d> centralBoxCorners(const std::vector<Eigen::Vector3d>& points) {
  if (points.empty()) return {};
  Eigen::Vector3d lo, hi;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> values;
    values.reserve(points.size());
    for (const Eigen::Vector3d& p : points) values.push_back(p[axis]);
    lo[axis] = percentile(values, 0.1);
    hi[axis] = percentile(values, 0.9);
  }
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i < 8; ++i)
    corners.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  return corners;
}

double aPosterioriFactor(const PinholeCamera& camera, const PoseTrackingResult& result) {
  if (!result.T_Ak || result.supportPointsA.empty() || !std::isfinite(result.supportSdPx) ||
      !(result.supportSdPx > 0))
    return 1.0;
  const std::optional<double> atSupport =
      predictedOverlayErrorPx(camera, *result.T_Ak, result.covariance, result.supportPointsA);
  if (!atSupport || !(*atSupport > 0)) return 1.0;
  return std::sqrt(2.0) * result.supportSdPx / *atSupport;  // supportSdPx is per image axis
}

OverlayErrorCheck checkPredictedOverlayError(const PinholeCamera& camera,
                                             const PoseTrackingResult& result,
                                             const std::vector<Eigen::Vector3d>& worldPoints,
                                             const PoseParams& params) {
  OverlayErrorCheck check;
  if (result.state != TrackingState::Tracking || !result.worldToCamera || !result.T_Ak)
    return check;
  const RigidPose T_A = result.T_Ak->inverse() * *result.worldToCamera;
  std::vector<Eigen::Vector3d> inCameraA;
  inCameraA.reserve(worldPoints.size());
  for (const Eigen::Vector3d& X : worldPoints) inCameraA.push_back(T_A * X);
  const std::optional<double> raw =
      predictedOverlayErrorPx(camera, *result.T_Ak, result.covariance, inCameraA);
  if (!raw) return check;
  check.predictedErrorPx = params.predictedErrorScale * aPosterioriFactor(camera, result) * *raw;
  if (params.maxPredictedErrorPx > 0 && *check.predictedErrorPx > params.maxPredictedErrorPx) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "predicted overlay error %.2f px > pose.max_predicted_error_px %g",
                  *check.predictedErrorPx, params.maxPredictedErrorPx);
    check.uncertainReason = text;
  }
  return check;
}

}  // namespace reftrack
