#include "render/PointMarkers.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "render/RenderTarget.hpp"
#include "render/RenderTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::render;

using PointMarkersTest = test::HeadlessGlTest;

TEST_F(PointMarkersTest, DotsLandOnProjectionsAndBehindCameraIsSkipped) {
  PinholeView view;
  view.K = test::testK();
  view.imageSize = test::testImageSize();
  view.worldToCamera = test::poseFrom(Eigen::Matrix3d::Identity(), {0.05, -0.02, 0.3});
  RenderTarget target(view.imageSize);
  target.bind();
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  const std::vector<Eigen::Vector3d> points = {{0, 0, 1}, {0.1, 0.05, 0.9}, {0, 0, -2}};
  PointMarkers markers;
  markers.draw(view, points, {cv::Scalar(255, 255, 255)}, 4);
  const cv::Mat image = target.readColourBgr();
  for (int i = 0; i < 2; ++i) {
    const Eigen::Vector2d expected = test::projectPoint(view.K, view.worldToCamera, points[i]);
    // Binary coverage of a symmetric disc: the centroid moves by well under half a pixel.
    EXPECT_LT((test::intensityCentroid(image, expected, 7) - expected).norm(), 0.25);
  }
  // Two discs of radius 4 cover about 2 * pi * 16 = 100 pixels; the point behind adds none.
  cv::Mat grey;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  EXPECT_NEAR(cv::countNonZero(grey), 2 * M_PI * 16, 12);
}

TEST_F(PointMarkersTest, ColourCountMustMatch) {
  PinholeView view;
  view.K = test::testK();
  view.imageSize = test::testImageSize();
  PointMarkers markers;
  EXPECT_THROW(markers.draw(view, {{0, 0, 1}, {0, 0, 2}}, {{1, 2, 3}, {1, 2, 3}, {1, 2, 3}}, 3),
               Error);
  EXPECT_THROW(markers.draw(view, {{0, 0, 1}}, {{1, 2, 3}}, 0), Error);
}
