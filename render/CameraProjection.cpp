// Pixel-exact GL projection from K (formula derived in the header).
#include "render/CameraProjection.hpp"

#include <Eigen/Geometry>
#include <cmath>
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

}  // namespace reftrack::render
