#include "render/SceneRenderer.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <iostream>

#include "engine/core/Error.hpp"
#include "render/RenderTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::render;
using test::HeadlessGlTest;

namespace {

struct BlobCase {
  Eigen::Vector3d centre;  // world point the blob is centred on
  Eigen::Matrix3d axes;    // orientation of the square
  double side;             // metres
};

Eigen::Matrix3d rotation(double degX, double degY, double degZ) {
  const double d = M_PI / 180.0;
  return (Eigen::AngleAxisd(degZ * d, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(degY * d, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(degX * d, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// Renders each blob alone and returns the largest distance between its intensity centroid and
// K(RX+t).
double worstCentroidError(SceneRenderer& renderer, const PinholeView& view,
                          const std::vector<BlobCase>& cases, int supersample) {
  double worst = 0;
  for (const BlobCase& c : cases) {
    renderer.clearMeshes();
    renderer.addMesh(test::texturedSquare(c.centre, c.axes, c.side, test::blobTexture()));
    const cv::Mat image = renderer.render(view, supersample);
    const Eigen::Vector2d expected = test::projectPoint(view.K, view.worldToCamera, c.centre);
    const Eigen::Vector2d centroid = test::intensityCentroid(image, expected, 14);
    const double error = (centroid - expected).norm();
    worst = std::max(worst, error);
  }
  return worst;
}

// Blobs across the image (centre, corners within 15 px of the border), at depths 0.6-2.5 m,
// fronto-parallel and tilted by up to 45 degrees, seen from a rotated camera.
std::vector<BlobCase> blobCases(const PinholeView& view) {
  const Eigen::Matrix3d R = view.worldToCamera.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = view.worldToCamera.topRightCorner<3, 1>();
  const Eigen::Matrix3d Kinv = view.K.inverse();
  std::vector<BlobCase> cases;
  const std::vector<std::tuple<double, double, double, Eigen::Matrix3d>> placements = {
      {160.3, 119.7, 1.0, Eigen::Matrix3d::Identity()}, {17.2, 16.6, 0.6, rotation(20, -10, 5)},
      {302.5, 18.1, 1.5, rotation(-45, 0, 0)},          {15.8, 223.4, 2.5, rotation(0, 40, 30)},
      {303.1, 224.9, 0.8, rotation(30, 30, 0)},         {97.4, 151.0, 1.2, rotation(0, -45, 10)}};
  for (const auto& [u, v, depth, tilt] : placements) {
    // Back-project the target pixel to the camera-frame point at `depth`, then to the world.
    const Eigen::Vector3d Xcam = depth * (Kinv * Eigen::Vector3d(u, v, 1));
    // Side chosen so the blob spans about 20 px (sigma 2.5 px) wherever it is.
    const double side = 20.0 * depth / view.K(0, 0);
    cases.push_back({R.transpose() * (Xcam - t), R.transpose() * tilt, side});
  }
  return cases;
}

PinholeView rotatedView() {
  PinholeView view;
  view.K = test::testK();
  view.imageSize = test::testImageSize();
  view.worldToCamera = test::poseFrom(rotation(10, -25, 40), Eigen::Vector3d(0.3, -0.2, 0.5));
  return view;
}

}  // namespace

using SceneRendererTest = HeadlessGlTest;

// A blob's intensity centroid equals its projected centre up to perspective skew of the blob
// (<= 4 f sigma^2 sin(tilt) / Z^2 ~ 0.03 px here) and 8-bit quantisation, so 0.1 px catches any
// half-pixel or principal-point mistake (those are >= 0.5 px).
TEST_F(SceneRendererTest, BlobCentroidsLandOnProjectedPoints) {
  SceneRenderer renderer;
  const PinholeView view = rotatedView();
  const double worst = worstCentroidError(renderer, view, blobCases(view), 1);
  std::cout << "worst centroid error (supersample 1): " << worst << " px\n";
  EXPECT_LT(worst, 0.1);
}

TEST_F(SceneRendererTest, BlobCentroidsLandOnProjectedPointsWhenSupersampled) {
  SceneRenderer renderer;
  const PinholeView view = rotatedView();
  const double worst = worstCentroidError(renderer, view, blobCases(view), 3);
  std::cout << "worst centroid error (supersample 3): " << worst << " px\n";
  EXPECT_LT(worst, 0.1);
}

// 24-bit depth with near 0.01 m, far 100 m resolves ~1e-5 m at 1 m; 1 mm leaves margin for
// the float pipeline.
TEST_F(SceneRendererTest, DepthReadbackIsCameraZ) {
  SceneRenderer renderer;
  PinholeView view = rotatedView();
  view.worldToCamera = Eigen::Matrix4d::Identity();
  // A plane through (0,0,1) tilted 30 degrees about the camera's y axis.
  const Eigen::Matrix3d tilt = rotation(0, 30, 0);
  renderer.addMesh(test::texturedSquare({0, 0, 1}, tilt, 0.6, test::blobTexture()));
  for (int supersample : {1, 3}) {
    cv::Mat depth;
    renderer.render(view, supersample, &depth);
    ASSERT_EQ(depth.type(), CV_32F);
    ASSERT_EQ(depth.size(), view.imageSize);
    const Eigen::Vector3d normal = tilt.col(2);
    const Eigen::Matrix3d Kinv = view.K.inverse();
    double worst = 0;
    for (const auto& [u, v] : std::vector<std::pair<int, int>>{{160, 120}, {100, 60}, {220, 180}}) {
      const Eigen::Vector3d ray = Kinv * Eigen::Vector3d(u, v, 1);  // z = 1
      const double z = normal.dot(Eigen::Vector3d(0, 0, 1)) / normal.dot(ray);
      worst = std::max(worst, std::abs(depth.at<float>(v, u) - z));
    }
    std::cout << "worst depth error (supersample " << supersample << "): " << worst * 1000
              << " mm\n";
    EXPECT_LT(worst, 1e-3);
    EXPECT_EQ(depth.at<float>(2, 2), 0.0f) << "an empty pixel must read 0";
  }
}

TEST_F(SceneRendererTest, NearerSurfaceHidesFartherWhateverTheDrawOrder) {
  const cv::Mat red(8, 8, CV_8UC3, cv::Scalar(0, 0, 255)),
      green(8, 8, CV_8UC3, cv::Scalar(0, 255, 0));
  PinholeView view = rotatedView();
  view.worldToCamera = Eigen::Matrix4d::Identity();
  for (bool nearFirst : {true, false}) {
    SceneRenderer renderer;
    const auto nearSquare =
        test::texturedSquare({0, 0, 1.0}, Eigen::Matrix3d::Identity(), 0.2, red);
    const auto farSquare =
        test::texturedSquare({0, 0, 1.5}, Eigen::Matrix3d::Identity(), 1.0, green);
    renderer.addMesh(nearFirst ? nearSquare : farSquare);
    renderer.addMesh(nearFirst ? farSquare : nearSquare);
    const cv::Mat image = renderer.render(view);
    EXPECT_EQ(image.at<cv::Vec3b>(120, 160), cv::Vec3b(0, 0, 255)) << "near first: " << nearFirst;
    EXPECT_EQ(image.at<cv::Vec3b>(120, 30), cv::Vec3b(0, 255, 0)) << "near first: " << nearFirst;
  }
}

TEST_F(SceneRendererTest, ClearColourFillsEmptyPixels) {
  SceneRenderer renderer;
  const cv::Mat image = renderer.render(rotatedView(), 1, nullptr, cv::Scalar(10, 20, 30));
  ASSERT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(image.at<cv::Vec3b>(0, 0), cv::Vec3b(10, 20, 30));
}

TEST_F(SceneRendererTest, RejectsBadMeshesAndViews) {
  SceneRenderer renderer;
  auto mesh =
      test::texturedSquare({0, 0, 1}, Eigen::Matrix3d::Identity(), 0.1, test::blobTexture());
  auto badUvs = mesh;
  badUvs.uvs.pop_back();
  EXPECT_THROW(renderer.addMesh(badUvs), Error);
  auto badIndex = mesh;
  badIndex.indices[0] = 99;
  EXPECT_THROW(renderer.addMesh(badIndex), Error);
  auto noTexture = mesh;
  noTexture.texture = cv::Mat();
  EXPECT_THROW(renderer.addMesh(noTexture), Error);
  auto nanPosition = mesh;
  nanPosition.positions[1].x() = NAN;
  EXPECT_THROW(renderer.addMesh(nanPosition), Error);
  PinholeView view = rotatedView();
  EXPECT_THROW(renderer.render(view, 0), Error);
  view.K(0, 0) = NAN;
  EXPECT_THROW(renderer.render(view), Error);
  view = rotatedView();
  view.nearPlane = 0;
  EXPECT_THROW(renderer.render(view), Error);
  view = rotatedView();
  view.imageSize = {0, 10};
  EXPECT_THROW(renderer.render(view), Error);
}
