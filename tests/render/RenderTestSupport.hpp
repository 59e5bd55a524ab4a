#pragma once
// Shared helpers for the render tests: a headless GL context per test, a test camera, poses,
// textured "blob squares" whose intensity centroid marks a known 3-D point, and image centroids.
#include <glad/gl.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "render/SceneRenderer.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::test {

// A headless context made before and destroyed after everything the test creates.
class HeadlessGlTest : public ::testing::Test {
 protected:
  void SetUp() override { context_ = render::createHeadlessContext(); }
  void TearDown() override { context_.reset(); }
  std::unique_ptr<render::GlContext> context_;
};

// Distinct fx/fy and non-integer principal point, so half-pixel and axis mix-ups show.
inline Eigen::Matrix3d testK() {
  Eigen::Matrix3d K;
  K << 400.0, 0.0, 160.3, 0.0, 410.0, 119.7, 0.0, 0.0, 1.0;
  return K;
}
inline cv::Size testImageSize() { return {320, 240}; }

inline Eigen::Matrix4d poseFrom(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = R;
  T.topRightCorner<3, 1>() = t;
  return T;
}

inline Eigen::Vector2d projectPoint(const Eigen::Matrix3d& K, const Eigen::Matrix4d& worldToCamera,
                                    const Eigen::Vector3d& X) {
  const Eigen::Vector3d x =
      K * (worldToCamera.topLeftCorner<3, 3>() * X + worldToCamera.topRightCorner<3, 1>());
  return x.hnormalized();
}

// A Gaussian blob (sigma = 1/8 of the side) on black, symmetric about the texture centre.
inline cv::Mat blobTexture(int side = 64) {
  cv::Mat texture(side, side, CV_8UC1);
  const double centre = (side - 1) / 2.0, sigma = side / 8.0;
  for (int r = 0; r < side; ++r)
    for (int c = 0; c < side; ++c)
      texture.at<uchar>(r, c) = cv::saturate_cast<uchar>(
          255.0 * std::exp(-((r - centre) * (r - centre) + (c - centre) * (c - centre)) /
                           (2 * sigma * sigma)));
  return texture;
}

// A square of side `side` centred on `centre`, spanned by the first two columns of `axes`.
inline render::TexturedMesh texturedSquare(const Eigen::Vector3d& centre,
                                           const Eigen::Matrix3d& axes, double side,
                                           const cv::Mat& texture) {
  render::TexturedMesh mesh;
  const Eigen::Vector3d a = axes.col(0) * side / 2, b = axes.col(1) * side / 2;
  mesh.positions = {(centre - a - b).cast<float>(), (centre + a - b).cast<float>(),
                    (centre + a + b).cast<float>(), (centre - a + b).cast<float>()};
  mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  mesh.texture = texture;
  return mesh;
}

// Intensity-weighted centroid of a grey or BGR image inside a window around `around`.
inline Eigen::Vector2d intensityCentroid(const cv::Mat& image, const Eigen::Vector2d& around,
                                         int radius) {
  cv::Mat grey;
  if (image.channels() == 3) {
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  } else {
    grey = image;
  }
  double sum = 0, sumX = 0, sumY = 0;
  const int cx = static_cast<int>(std::lround(around.x())),
            cy = static_cast<int>(std::lround(around.y()));
  for (int y = std::max(0, cy - radius); y <= std::min(grey.rows - 1, cy + radius); ++y)
    for (int x = std::max(0, cx - radius); x <= std::min(grey.cols - 1, cx + radius); ++x) {
      const double w = grey.at<uchar>(y, x);
      sum += w;
      sumX += w * x;
      sumY += w * y;
    }
  if (sum <= 0) return {NAN, NAN};
  return {sumX / sum, sumY / sum};
}

}  // namespace reftrack::test
