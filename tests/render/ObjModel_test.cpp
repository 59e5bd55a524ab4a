#include "render/ObjModel.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <fstream>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"
#include "engine/core/Error.hpp"
#include "render/RenderTarget.hpp"
#include "render/RenderTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::render;

namespace {

std::filesystem::path modelsDir() { return test::sourceDir() / "assets" / "models"; }

std::string loadError(const std::filesystem::path& file) {
  return test::errorMessage([&] { loadObjMesh(file); });
}

std::filesystem::path writeText(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return file;
}

PinholeView modelView() {
  PinholeView view;
  view.K = test::testK();
  view.imageSize = test::testImageSize();
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitY()))
                                .toRotationMatrix();
  view.worldToCamera = test::poseFrom(R, {0.02, 0.01, 0.8});
  return view;
}

cv::Mat renderModel(ObjModel& model, const PinholeView& view, const ObjDrawOptions& options) {
  RenderTarget target(view.imageSize);
  target.bind();
  glClearColor(0, 0, 0, 1);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  model.draw(view, options);
  return target.readColourBgr();
}

}  // namespace

TEST(ObjModel, LoadsShippedModels) {
  const LitMesh cube = loadObjMesh(modelsDir() / "cube.obj");
  EXPECT_EQ(cube.positions.size(), 36u);  // 6 quads -> 12 triangles
  // Material Kd from cube.mtl.
  EXPECT_NEAR(cube.diffuse[0].z(), 0.9f, 1e-6);
  const LitMesh house = loadObjMesh(modelsDir() / "house.obj");
  EXPECT_EQ(house.positions.size(), 18u * 3);  // 5 wall quads, 2 gables, 2 roof quads, a door
  // house.obj has no normals: flat normals are computed, unit length and perpendicular.
  for (size_t t = 0; t < house.positions.size(); t += 3) {
    const Eigen::Vector3f edge = house.positions[t + 1] - house.positions[t];
    EXPECT_NEAR(house.normals[t].norm(), 1.0f, 1e-5);
    EXPECT_NEAR(house.normals[t].dot(edge), 0.0f, 1e-5);
  }
}

TEST(ObjModel, BadFilesGiveClearErrors) {
  const auto dir = test::freshTempDir("ObjModel_BadFiles");
  EXPECT_NE(loadError(dir / "absent.obj").find("does not exist"), std::string::npos);
  EXPECT_NE(loadError(writeText(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"))
                .find("contains no triangles"),
            std::string::npos);
  EXPECT_NE(loadError(writeText(dir / "garbage.obj", "\x01\x02 not an obj at all\n"))
                .find("contains no triangles"),
            std::string::npos);
  const std::string outOfRange =
      loadError(writeText(dir / "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"));
  EXPECT_NE(outOfRange.find("range.obj"), std::string::npos) << outOfRange;
  EXPECT_NE(loadError(writeText(dir / "huge.obj", "v 0 0 1e400\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"))
                .find("non-finite"),
            std::string::npos);
}

using ObjModelTest = test::HeadlessGlTest;

// A convex cube covers exactly the convex hull of its projected vertices. Rasterisation decides
// edge pixels by their centres, so only pixels within 1 px of the hull boundary may differ.
TEST_F(ObjModelTest, RenderedCubeCoversItsProjectedHull) {
  ObjModel cube(modelsDir() / "cube.obj");
  EXPECT_EQ(cube.triangleCount(), 12u);
  const PinholeView view = modelView();
  ObjDrawOptions options;
  options.transform.scale = 0.2;
  options.transform.offset = {0.03, -0.02, 0.05};
  const cv::Mat image = renderModel(cube, view, options);

  std::vector<cv::Point2f> projected;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d model((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? 0.5 : -0.5);
    const Eigen::Vector3d world =
        options.transform.modelToWorld().topLeftCorner<3, 3>() * model + options.transform.offset;
    const Eigen::Vector2d p = test::projectPoint(view.K, view.worldToCamera, world);
    projected.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
  }
  std::vector<cv::Point2f> hull;
  cv::convexHull(projected, hull);
  cv::Mat rendered;
  cv::cvtColor(image, rendered, cv::COLOR_BGR2GRAY);
  rendered = rendered > 0;
  int inner = 0, outer = 0, wrong = 0;
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x) {
      const double distance = cv::pointPolygonTest(hull, cv::Point2f(x, y), true);
      const bool covered = rendered.at<uchar>(y, x) != 0;
      if (distance > 1.0) {
        ++inner;
        wrong += covered ? 0 : 1;
      } else if (distance < -1.0) {
        ++outer;
        wrong += covered ? 1 : 0;
      }
    }
  EXPECT_GT(inner, 2000);
  EXPECT_EQ(wrong, 0) << "pixels off the projected hull by more than 1 px";
}

TEST_F(ObjModelTest, HouseShowsItsMaterialsAndWireframeOverlay) {
  ObjModel house(modelsDir() / "house.obj");
  EXPECT_EQ(house.triangleCount(), 18u);
  PinholeView view = modelView();
  // Front view of the house (OBJ y up -> camera y down: rotate 180 degrees about x).
  view.worldToCamera = test::poseFrom(
      Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix(), {0, 0.05, 0.9});
  ObjDrawOptions options;
  options.transform.scale = 0.3;
  options.transform.offset = {0, 0, -0.05};
  const cv::Mat plain = renderModel(house, view, options);
  // The roof (Kd 0.70 0.15 0.10) is red-dominant, the walls (0.90 0.85 0.70) are not.
  const Eigen::Vector2d roof = test::projectPoint(view.K, view.worldToCamera, {0, 0.26, 0.03});
  const cv::Vec3b roofPixel =
      plain.at<cv::Vec3b>(static_cast<int>(roof.y()), static_cast<int>(roof.x()));
  EXPECT_GT(roofPixel[2], 2 * roofPixel[1]) << roofPixel;
  const Eigen::Vector2d wall = test::projectPoint(view.K, view.worldToCamera, {0.1, 0.15, 0.07});
  const cv::Vec3b wallPixel =
      plain.at<cv::Vec3b>(static_cast<int>(wall.y()), static_cast<int>(wall.x()));
  EXPECT_LT(wallPixel[2], 2 * wallPixel[1]) << wallPixel;
  EXPECT_GT(wallPixel[1], 60) << wallPixel;

  options.wireframe = true;
  options.wireframeColourBgr = cv::Scalar(0, 255, 0);
  const cv::Mat wired = renderModel(house, view, options);
  cv::Mat green;
  cv::inRange(wired, cv::Scalar(0, 255, 0), cv::Scalar(0, 255, 0), green);
  EXPECT_GT(cv::countNonZero(green), 200);
}

TEST_F(ObjModelTest, RejectsBadTransforms) {
  ObjModel cube(modelsDir() / "cube.obj");
  ObjDrawOptions options;
  options.transform.scale = 0;
  EXPECT_THROW(cube.draw(modelView(), options), Error);
  options = {};
  options.transform.rotation(0, 0) = 2;
  EXPECT_THROW(cube.draw(modelView(), options), Error);
  options = {};
  options.ambient = 1.5;
  EXPECT_THROW(cube.draw(modelView(), options), Error);
  EXPECT_THROW(ObjModel(LitMesh{}), Error);
}

namespace {

// Pixels more than 1 px inside the hull of `points` left empty plus pixels more than 1 px
// outside it covered.
int hullMismatch(const cv::Mat& image, const std::vector<cv::Point2f>& points) {
  std::vector<cv::Point2f> hull;
  cv::convexHull(points, hull);
  cv::Mat grey;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  int wrong = 0;
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x) {
      const double distance = cv::pointPolygonTest(hull, cv::Point2f(x, y), true);
      const bool covered = grey.at<uchar>(y, x) != 0;
      if ((distance > 1.0 && !covered) || (distance < -1.0 && covered)) ++wrong;
    }
  return wrong;
}

}  // namespace

// Through a k1 = -0.3 lens each vertex of the cube lands where cv::projectPoints puts it (the
// vertex shader applies OpenCV's model), so the silhouette is the hull of the distorted vertices
// (its edges are straight between them: the cube's faces are single quads) and not the pinhole
// one.
TEST_F(ObjModelTest, DistortedCubeCoversTheHullOfItsDistortedVertices) {
  ObjModel cube(modelsDir() / "cube.obj");
  PinholeView view = modelView();
  view.distortion = {-0.3, 0.0, 0.0, 0.0};
  ObjDrawOptions options;
  options.transform.scale = 0.2;
  options.transform.offset = {0.18, 0.1, 0.05};  // off-centre, where the lens bends more
  const cv::Mat image = renderModel(cube, view, options);
  cv::Matx33d K;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) K(r, c) = view.K(r, c);
  std::vector<cv::Point2f> distorted, ideal;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d model((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? 0.5 : -0.5);
    const Eigen::Vector3d world =
        options.transform.modelToWorld().topLeftCorner<3, 3>() * model + options.transform.offset;
    const Eigen::Vector3d Xc = view.worldToCamera.topLeftCorner<3, 3>() * world +
                               view.worldToCamera.topRightCorner<3, 1>();
    std::vector<cv::Point2d> p;
    cv::projectPoints(std::vector<cv::Point3d>{{Xc.x(), Xc.y(), Xc.z()}}, cv::Vec3d::all(0),
                      cv::Vec3d::all(0), K, view.distortion, p);
    distorted.emplace_back(static_cast<float>(p[0].x), static_cast<float>(p[0].y));
    const Eigen::Vector2d q = test::projectPoint(view.K, view.worldToCamera, world);
    ideal.emplace_back(static_cast<float>(q.x()), static_cast<float>(q.y()));
  }
  EXPECT_EQ(hullMismatch(image, distorted), 0);
  EXPECT_GT(hullMismatch(image, ideal), 50);  // the pinhole hull does not fit: not vacuous
}
