#include "render/WireframeCube.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <iostream>
#include <opencv2/calib3d.hpp>

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

namespace {

// The camera of a wide webcam: 640x480, 50 degrees, k1 = -0.3.
PinholeView distortedView() {
  PinholeView view;
  const double f = 320.0 / std::tan(25.0 * M_PI / 180.0);
  view.K << f, 0, 319.5, 0, f, 239.5, 0, 0, 1;
  view.imageSize = {640, 480};
  view.distortion = {-0.3, 0.0, 0.0, 0.0};
  return view;
}

Eigen::Vector2d projectThroughOpenCv(const PinholeView& view, const Eigen::Vector3d& X) {
  cv::Matx33d K;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) K(r, c) = view.K(r, c);
  const Eigen::Vector3d Xc =
      view.worldToCamera.topLeftCorner<3, 3>() * X + view.worldToCamera.topRightCorner<3, 1>();
  std::vector<cv::Point2d> p;
  cv::projectPoints(std::vector<cv::Point3d>{{Xc.x(), Xc.y(), Xc.z()}}, cv::Vec3d::all(0),
                    cv::Vec3d::all(0), K, view.distortion, p);
  return {p[0].x, p[0].y};
}

}  // namespace

// k1 = -0.3: a cube in each image corner (one vertex 8 px from the corner, the cube reaching
// inwards) and one in the centre. Every vertex dot's centroid is within 0.5 px of
// cv::projectPoints (same disc-sampling argument as above), and the midpoint of every edge's
// curved image is covered by the edge, while the straight chord between its ends misses it by
// pixels at the corners (the edges bend as the lens bends them).
TEST_F(WireframeCubeTest, DistortedVerticesAndEdgesLandWhereTheLensPutsThem) {
  PinholeView view = distortedView();
  std::vector<cv::Point2f> targets = {{8, 8}, {631, 8}, {8, 471}, {631, 471}, {319.5f, 239.5f}};
  std::vector<cv::Point2f> rays;
  cv::Matx33d K;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) K(r, c) = view.K(r, c);
  cv::undistortPoints(targets, rays, K, view.distortion, cv::noArray(), cv::noArray(),
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-6));
  const double h = 0.05, depth = 0.5;
  double worstVertex = 0.0, worstEdge = 0.0, largestBend = 0.0;
  int vertexCount = 0;
  for (std::size_t c = 0; c < targets.size(); ++c) {
    // The target vertex: -x/+x towards the left/right edge, -y/+y towards the top/bottom, front.
    const double sx = targets[c].x < 300 ? -1 : 1, sy = targets[c].y < 200 ? -1 : 1;
    const Eigen::Vector3d vertex(rays[c].x * depth, rays[c].y * depth, depth);
    WireframeCubeStyle style;
    style.edgeLength = 2 * h;
    style.modelToWorld.topRightCorner<3, 1>() = vertex - h * Eigen::Vector3d(sx, sy, -1);
    RenderTarget target(view.imageSize);
    target.bind();
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    WireframeCube cube;
    cube.draw(view, style);
    const cv::Mat image = target.readColourBgr();
    const auto vertices = WireframeCube::worldVertices(style);
    std::vector<Eigen::Vector2d> projected;
    for (const Eigen::Vector3d& X : vertices) projected.push_back(projectThroughOpenCv(view, X));
    for (int i = 0; i < 8; ++i) {
      const Eigen::Vector2d expected = projected[static_cast<size_t>(i)];
      if (expected.x() < 6 || expected.y() < 6 || expected.x() > 633 || expected.y() > 473)
        continue;            // the dot would be cut by the image border
      bool isolated = true;  // a dot partly covered by a later vertex's dot is not measured
      for (int j = 0; j < 8; ++j)
        if (j != i && (projected[static_cast<size_t>(j)] - expected).norm() < 12) isolated = false;
      if (!isolated) continue;
      const cv::Scalar colour = WireframeCube::vertexColoursBgr()[static_cast<size_t>(i)];
      cv::Mat mask;
      cv::inRange(image, colour, colour, mask);
      const cv::Moments m = cv::moments(mask, true);
      ASSERT_GT(m.m00, 40) << "cube " << c << " vertex " << i;
      const Eigen::Vector2d centroid(m.m10 / m.m00, m.m01 / m.m00);
      worstVertex = std::max(worstVertex, (centroid - expected).norm());
      ++vertexCount;
    }
    for (int i = 0; i < 8; ++i)
      for (int bit : {1, 2, 4}) {
        if (i & bit) continue;
        const Eigen::Vector2d a = projectThroughOpenCv(view, vertices[i]);
        const Eigen::Vector2d b = projectThroughOpenCv(view, vertices[i | bit]);
        const Eigen::Vector2d mid =
            projectThroughOpenCv(view, 0.5 * (vertices[i] + vertices[i | bit]));
        if (mid.x() < 2 || mid.y() < 2 || mid.x() > 637 || mid.y() > 477) continue;
        if ((a - b).norm() < 12) continue;  // seen end-on: under the vertex dots
        largestBend = std::max(largestBend, (0.5 * (a + b) - mid).norm());
        // Distance from `mid` to the nearest edge-coloured pixel.
        cv::Mat edge;
        cv::inRange(image, style.colourBgr, style.colourBgr, edge);
        double nearest = 1e9;
        for (int y = static_cast<int>(mid.y()) - 4; y <= static_cast<int>(mid.y()) + 4; ++y)
          for (int x = static_cast<int>(mid.x()) - 4; x <= static_cast<int>(mid.x()) + 4; ++x)
            if (x >= 0 && y >= 0 && x < 640 && y < 480 && edge.at<uchar>(y, x))
              nearest = std::min(nearest, std::hypot(x - mid.x(), y - mid.y()));
        worstEdge = std::max(worstEdge, nearest);
      }
  }
  std::cout << vertexCount << " vertices: worst dot error " << worstVertex
            << " px; edge midpoints: worst distance to the drawn edge " << worstEdge
            << " px, largest bend " << largestBend << " px\n";
  EXPECT_GE(vertexCount, 20);
  EXPECT_LT(worstVertex, 0.5);
  // The curve's midpoint lies within the 3 px wide line: a covered pixel centre within 1 px.
  EXPECT_LE(worstEdge, 1.0);
  EXPECT_GT(largestBend, 2.0);  // a straight chord would miss it: the check is not vacuous
}
