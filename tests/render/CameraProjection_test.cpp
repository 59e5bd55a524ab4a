#include "render/CameraProjection.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "engine/core/Error.hpp"
#include "render/RenderTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::render;

namespace {

// Pixel (u, v) from clip coordinates via the viewport transform (fragment centres at i + 0.5,
// window row 0 at the bottom, image row 0 at the top).
Eigen::Vector2d pixelFromClip(const Eigen::Vector4d& clip, cv::Size size) {
  const Eigen::Vector3d ndc = clip.hnormalized();
  return {size.width * (ndc.x() + 1) / 2 - 0.5, size.height * (1 - ndc.y()) / 2 - 0.5};
}

}  // namespace

// Pure arithmetic in double: 1e-9 px is rounding only.
TEST(CameraProjection, CameraPointLandsOnKXOverZ) {
  Eigen::Matrix3d K = test::testK();
  K(0, 1) = 1.5;  // skew too
  const cv::Size size = test::testImageSize();
  const Eigen::Matrix4d P = glProjectionFromK(K, size, 0.05, 20.0) * openCvToGlCamera();
  for (const Eigen::Vector3d& X : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0.3, -0.2, 2.0),
                                   Eigen::Vector3d(-1.0, 0.7, 4.5)}) {
    const Eigen::Vector2d expected = (K * X).hnormalized();
    const Eigen::Vector2d got = pixelFromClip(P * X.homogeneous(), size);
    EXPECT_LT((got - expected).norm(), 1e-9) << X.transpose();
  }
}

TEST(CameraProjection, DepthMapsBackToCameraZ) {
  const double n = 0.05, f = 20.0;
  const Eigen::Matrix4d P =
      glProjectionFromK(test::testK(), test::testImageSize(), n, f) * openCvToGlCamera();
  for (double Z : {0.05, 0.5, 1.0, 7.3, 19.9}) {
    const Eigen::Vector4d clip = P * Eigen::Vector4d(0.1, 0.1, Z, 1);
    const double d = (clip.z() / clip.w() + 1) / 2;  // glDepthRange(0, 1)
    EXPECT_NEAR(depthBufferToMetres(d, n, f), Z, 1e-9 * Z);
  }
  EXPECT_EQ(depthBufferToMetres(1.0, n, f), 0.0);
}

TEST(CameraProjection, ViewProjectionAppliesWorldToCamera) {
  const Eigen::Matrix3d K = test::testK();
  const cv::Size size = test::testImageSize();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  const Eigen::Matrix4d T = test::poseFrom(R, {0.1, 0.2, 1.5});
  const Eigen::Vector3d X(0.2, -0.1, 0.3);
  const Eigen::Vector2d got =
      pixelFromClip(glViewProjection(K, size, T, 0.01, 100) * X.homogeneous(), size);
  EXPECT_LT((got - test::projectPoint(K, T, X)).norm(), 1e-9);
}

TEST(CameraProjection, SupersampledKKeepsPixelCentres) {
  const Eigen::Matrix3d K = test::testK();
  const Eigen::Matrix3d K3 = supersampledK(K, 3);
  const Eigen::Vector3d X(0.2, -0.1, 1.3);
  const Eigen::Vector2d u = (K * X).hnormalized(), u3 = (K3 * X).hnormalized();
  // Pixel u covers [3u, 3u+2] + ... in the big image: its centre is 3u + 1.
  EXPECT_LT((u3 - (3 * u + Eigen::Vector2d(1, 1))).norm(), 1e-9);
  EXPECT_EQ(supersampledK(K, 1), K);
  EXPECT_THROW(supersampledK(K, 0), Error);
}

TEST(CameraProjection, RejectsBadInputsNamingThem) {
  const Eigen::Matrix3d K = test::testK();
  const cv::Size size = test::testImageSize();
  auto message = [](auto&& call) -> std::string {
    try {
      call();
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  Eigen::Matrix3d bad = K;
  bad(0, 0) = -1;
  EXPECT_NE(message([&] { glProjectionFromK(bad, size, 0.1, 10); }).find("fx"), std::string::npos);
  bad = K;
  bad(1, 2) = NAN;
  EXPECT_NE(message([&] { glProjectionFromK(bad, size, 0.1, 10); }).find("non-finite"),
            std::string::npos);
  EXPECT_NE(message([&] {
              glProjectionFromK(K, {0, 5}, 0.1, 10);
            }).find("image size"),
            std::string::npos);
  EXPECT_NE(message([&] { glProjectionFromK(K, size, 0, 10); }).find("near"), std::string::npos);
  EXPECT_NE(message([&] { glProjectionFromK(K, size, 1, 1); }).find("far"), std::string::npos);
  Eigen::Matrix4d pose = Eigen::Matrix4d::Identity();
  pose(0, 3) = INFINITY;
  EXPECT_NE(message([&] { glViewProjection(K, size, pose, 0.1, 10); }).find("pose"),
            std::string::npos);
}
