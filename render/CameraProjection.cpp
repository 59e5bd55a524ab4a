// Pixel-exact GL projection from K (formula derived in the header).
#include "render/CameraProjection.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <string>

#include "engine/core/Error.hpp"

namespace reftrack::render {

namespace {

void checkIntrinsics(const Eigen::Matrix3d& K) {
  if (!K.allFinite()) throw Error("camera matrix K has a non-finite entry");
  if (!(K(0, 0) > 0)) throw Error("camera matrix K: fx must be positive");
  if (!(K(1, 1) > 0)) throw Error("camera matrix K: fy must be positive");
  if (K(1, 0) != 0 || K(2, 0) != 0 || K(2, 1) != 0 || K(2, 2) != 1)
    throw Error("camera matrix K must be upper triangular with K(2,2) = 1");
}

}  // namespace

Eigen::Matrix4d glProjectionFromK(const Eigen::Matrix3d& K, cv::Size imageSize, double nearPlane,
                                  double farPlane) {
  checkIntrinsics(K);
  if (imageSize.width <= 0 || imageSize.height <= 0)
    throw Error("image size must be positive, got " + std::to_string(imageSize.width) + "x" +
                std::to_string(imageSize.height));
  if (!std::isfinite(nearPlane) || !(nearPlane > 0))
    throw Error("near plane must be a positive distance");
  if (!std::isfinite(farPlane) || !(farPlane > nearPlane))
    throw Error("far plane must be finite and beyond the near plane");
  const double W = imageSize.width, H = imageSize.height, n = nearPlane, f = farPlane;
  Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
  P(0, 0) = 2 * K(0, 0) / W;
  P(0, 1) = -2 * K(0, 1) / W;
  P(0, 2) = 1 - 2 * (K(0, 2) + 0.5) / W;
  P(1, 1) = 2 * K(1, 1) / H;
  P(1, 2) = 2 * (K(1, 2) + 0.5) / H - 1;
  P(2, 2) = -(f + n) / (f - n);
  P(2, 3) = -2 * f * n / (f - n);
  P(3, 2) = -1;
  return P;
}

Eigen::Matrix4d openCvToGlCamera() { return Eigen::Vector4d(1, -1, -1, 1).asDiagonal(); }

Eigen::Matrix4d glViewProjection(const Eigen::Matrix3d& K, cv::Size imageSize,
                                 const Eigen::Matrix4d& worldToCamera, double nearPlane,
                                 double farPlane) {
  if (!worldToCamera.allFinite()) throw Error("world-to-camera pose has a non-finite entry");
  return glProjectionFromK(K, imageSize, nearPlane, farPlane) * openCvToGlCamera() * worldToCamera;
}

Eigen::Matrix3d supersampledK(const Eigen::Matrix3d& K, int factor) {
  if (factor < 1) throw Error("supersample factor must be >= 1, got " + std::to_string(factor));
  const double s = factor;
  Eigen::Matrix3d scaled = K;
  scaled.topRows<2>() *= s;
  scaled(0, 2) += (s - 1) / 2;
  scaled(1, 2) += (s - 1) / 2;
  return scaled;
}

double depthBufferToMetres(double d, double nearPlane, double farPlane) {
  if (d >= 1.0) return 0.0;
  return farPlane * nearPlane / (farPlane - d * (farPlane - nearPlane));
}

std::optional<Eigen::Vector2d> projectToPixel(const Eigen::Matrix3d& K,
                                              const Eigen::Matrix4d& worldToCamera,
                                              const Eigen::Vector3d& worldPoint, double nearPlane) {
  const Eigen::Vector3d X =
      worldToCamera.topLeftCorner<3, 3>() * worldPoint + worldToCamera.topRightCorner<3, 1>();
  if (!(X.z() > nearPlane)) return std::nullopt;
  return (K * X).hnormalized();
}

std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> projectSegmentToPixels(
    const Eigen::Matrix3d& K, const Eigen::Matrix4d& worldToCamera, const Eigen::Vector3d& a,
    const Eigen::Vector3d& b, double nearPlane) {
  const Eigen::Matrix3d R = worldToCamera.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = worldToCamera.topRightCorner<3, 1>();
  Eigen::Vector3d A = R * a + t, B = R * b + t;
  if (A.z() < nearPlane && B.z() < nearPlane) return std::nullopt;
  if (A.z() < nearPlane) A = B + (A - B) * ((nearPlane - B.z()) / (A.z() - B.z()));
  if (B.z() < nearPlane) B = A + (B - A) * ((nearPlane - A.z()) / (B.z() - A.z()));
  return std::make_pair(Eigen::Vector2d((K * A).hnormalized()),
                        Eigen::Vector2d((K * B).hnormalized()));
}

namespace {

bool hasDistortion(const std::vector<double>& distortion) {
  if (distortion.size() != 0 && distortion.size() != 4 && distortion.size() != 5 &&
      distortion.size() != 8)
    throw Error("lens distortion must have 0, 4, 5 or 8 coefficients, got " +
                std::to_string(distortion.size()));
  return std::any_of(distortion.begin(), distortion.end(), [](double d) { return d != 0.0; });
}

double radialDistortedRadius(const std::vector<double>& d, double r) {
  const double r2 = r * r, r4 = r2 * r2, r6 = r4 * r2;
  const auto at = [&](std::size_t i) { return i < d.size() ? d[i] : 0.0; };
  return r * (1 + at(0) * r2 + at(1) * r4 + at(4) * r6) /
         (1 + at(5) * r2 + at(6) * r4 + at(7) * r6);
}

}  // namespace

double lensValidRadius(const std::vector<double>& distortion) {
  if (!hasDistortion(distortion)) return std::numeric_limits<double>::infinity();
  constexpr double kStep = 1e-3, kLimit = 10.0;
  double previous = 0.0;
  for (double r = kStep; r <= kLimit; r += kStep) {
    const double rd = radialDistortedRadius(distortion, r);
    if (!(rd > previous)) return r - kStep;
    previous = rd;
  }
  return std::numeric_limits<double>::infinity();
}

std::vector<Eigen::Vector2d> projectThroughLens(const Eigen::Matrix3d& K,
                                                const std::vector<double>& distortion,
                                                const std::vector<Eigen::Vector3d>& cameraPoints) {
  std::vector<Eigen::Vector2d> pixels;
  pixels.reserve(cameraPoints.size());
  if (!hasDistortion(distortion)) {
    for (const Eigen::Vector3d& X : cameraPoints) pixels.push_back((K * X).hnormalized());
    return pixels;
  }
  checkIntrinsics(K);
  const double validRadius = lensValidRadius(distortion);
  std::vector<cv::Point3d> points;
  points.reserve(cameraPoints.size());
  for (const Eigen::Vector3d& X : cameraPoints) points.emplace_back(X.x(), X.y(), X.z());
  std::vector<cv::Point2d> projected;
  if (!points.empty()) {
    cv::Matx33d k;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) k(r, c) = K(r, c);
    cv::projectPoints(points, cv::Vec3d::all(0), cv::Vec3d::all(0), k, distortion, projected);
  }
  for (std::size_t i = 0; i < cameraPoints.size(); ++i) {
    const Eigen::Vector3d& X = cameraPoints[i];
    const bool valid = X.z() > 0 && X.head<2>().norm() <= validRadius * X.z();
    pixels.emplace_back(valid
                            ? Eigen::Vector2d(projected[i].x, projected[i].y)
                            : Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()));
  }
  return pixels;
}

std::optional<Eigen::Vector2d> projectToPixel(const Eigen::Matrix3d& K,
                                              const std::vector<double>& distortion,
                                              const Eigen::Matrix4d& worldToCamera,
                                              const Eigen::Vector3d& worldPoint, double nearPlane) {
  const Eigen::Vector3d X =
      worldToCamera.topLeftCorner<3, 3>() * worldPoint + worldToCamera.topRightCorner<3, 1>();
  if (!(X.z() > nearPlane)) return std::nullopt;
  return projectThroughLens(K, distortion, {X})[0];
}

std::vector<Eigen::Vector2d> projectSegmentThroughLens(const Eigen::Matrix3d& K,
                                                       const std::vector<double>& distortion,
                                                       const Eigen::Matrix4d& worldToCamera,
                                                       const Eigen::Vector3d& a,
                                                       const Eigen::Vector3d& b, double nearPlane,
                                                       double maxStepPx) {
  const Eigen::Matrix3d R = worldToCamera.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = worldToCamera.topRightCorner<3, 1>();
  Eigen::Vector3d A = R * a + t, B = R * b + t;
  if (A.z() < nearPlane && B.z() < nearPlane) return {};
  if (A.z() < nearPlane) A = B + (A - B) * ((nearPlane - B.z()) / (A.z() - B.z()));
  if (B.z() < nearPlane) B = A + (B - A) * ((nearPlane - A.z()) / (B.z() - A.z()));
  if (!hasDistortion(distortion)) return {(K * A).hnormalized(), (K * B).hnormalized()};
  if (!(maxStepPx > 0)) throw Error("segment through the lens: maxStepPx must be positive");
  const double idealLength = ((K * A).hnormalized() - (K * B).hnormalized()).norm();
  constexpr int kMaxPieces = 1024;
  const int pieces =
      std::isfinite(idealLength)
          ? std::clamp(static_cast<int>(std::ceil(idealLength / maxStepPx)), 1, kMaxPieces)
          : kMaxPieces;
  std::vector<Eigen::Vector3d> points;
  points.reserve(static_cast<std::size_t>(pieces) + 1);
  for (int i = 0; i <= pieces; ++i) points.push_back(A + (B - A) * (double(i) / pieces));
  return projectThroughLens(K, distortion, points);
}

}  // namespace reftrack::render
