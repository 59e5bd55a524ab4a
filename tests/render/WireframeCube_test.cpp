#include "render/WireframeCube.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <iostream>

#include "engine/core/Error.hpp"
#include "render/RenderTarget.hpp"
#include "render/RenderTestSupport.hpp"
#include "render/VideoBackground.hpp"

using namespace reftrack;
using namespace reftrack::render;

using WireframeCubeTest = test::HeadlessGlTest;

namespace {

PinholeView cubeView() {
  PinholeView view;
  view.K = test::testK();
  view.imageSize = test::testImageSize();
  // Looking at the origin from about 0.6 m, rotated so all 8 vertices are well apart.
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitY()))
                                .toRotationMatrix();
  view.worldToCamera = test::poseFrom(R, {0.01, -0.02, 0.6});
  return view;
}

}  // namespace

// Over a noisy background, each vertex dot's centroid (pixels of exactly its colour; the
// background stays within 30..200 so it never matches) is within 0.5 px of K[R|t]X: the dot is
// a point-symmetric 32-gon around the projected vertex, so only the binary sampling at pixel
// centres moves its centroid, by well under half a pixel for a radius of 5 px.
TEST_F(WireframeCubeTest, VertexDotsLandOnProjectedVertices) {
  const PinholeView view = cubeView();
  RenderTarget target(view.imageSize);
  target.bind();
  cv::Mat background(view.imageSize, CV_8UC3);
  cv::randu(background, 30, 201);
  VideoBackground video;
  video.draw(background);
  WireframeCubeStyle style;
  style.edgeLength = 0.2;
  style.modelToWorld(0, 3) = 0.01;
  WireframeCube cube;
  cube.draw(view, style);
  const cv::Mat image = target.readColourBgr();

  const auto vertices = WireframeCube::worldVertices(style);
  double worst = 0;
  for (int i = 0; i < 8; ++i) {
    const cv::Scalar colour = WireframeCube::vertexColoursBgr()[static_cast<size_t>(i)];
    cv::Mat mask;
    cv::inRange(image, colour, colour, mask);
    const cv::Moments m = cv::moments(mask, true);
    ASSERT_GT(m.m00, 40) << "vertex " << i << " dot missing or hidden";
    const Eigen::Vector2d centroid(m.m10 / m.m00, m.m01 / m.m00);
    const Eigen::Vector2d expected = test::projectPoint(view.K, view.worldToCamera, vertices[i]);
    worst = std::max(worst, (centroid - expected).norm());
  }
  std::cout << "worst vertex dot error: " << worst << " px\n";
  EXPECT_LT(worst, 0.5);
  // Edges are drawn too: the edge colour covers a good number of pixels.
  cv::Mat edges;
  cv::inRange(image, style.colourBgr, style.colourBgr, edges);
  EXPECT_GT(cv::countNonZero(edges), 500);
}

TEST_F(WireframeCubeTest, CubeCrossingTheNearPlaneStillDraws) {
  PinholeView view = cubeView();
  // The edges at model x = -0.1 pass through the optical axis region.
  view.worldToCamera = test::poseFrom(Eigen::Matrix3d::Identity(), {0.1, 0.1, 0.05});
  RenderTarget target(view.imageSize);
  target.bind();
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  WireframeCubeStyle style;
  style.edgeLength = 0.2;  // spans z = -0.05 .. 0.15 in the camera frame
  style.vertexDots = false;
  WireframeCube cube;
  cube.draw(view, style);
  cv::Mat grey;
  cv::cvtColor(target.readColourBgr(), grey, cv::COLOR_BGR2GRAY);
  EXPECT_GT(cv::countNonZero(grey), 100);
}

TEST_F(WireframeCubeTest, StyleCheckNamesField) {
  WireframeCubeStyle style;
  style.lineWidthPx = 0;
  try {
    style.check();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lineWidthPx"), std::string::npos);
  }
  style = {};
  style.edgeLength = NAN;
  EXPECT_THROW(style.check(), Error);
}
