#include "app/simulator/DistortingLens.hpp"

#include <gtest/gtest.h>

#include <iostream>
#include <opencv2/calib3d.hpp>

#include "engine/core/Error.hpp"
#include "render/CameraProjection.hpp"
#include "render/RenderTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

using DistortingLensTest = test::HeadlessGlTest;

constexpr int kSupersample = 3;  // as the simulator

PinholeCamera lensCamera(std::vector<double> distortion) {
  const PinholeCamera ideal = PinholeCamera::fromFieldOfView({640, 480}, 50.0);
  return PinholeCamera(ideal.K(), ideal.imageSize(), std::move(distortion));
}

// Blob centres (world, camera at the origin looking down +z) whose distorted images sit on a 7x5
// grid spanning the whole image, 16 px from its edges (the corner blobs lie in the corners).
std::vector<Eigen::Vector3d> blobCentres(const PinholeCamera& camera) {
  std::vector<cv::Point2f> pixels;
  const cv::Size size = camera.imageSize();
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 7; ++i)
      pixels.emplace_back(16.0f + i * (size.width - 33.0f) / 6.0f,
                          16.0f + j * (size.height - 33.0f) / 4.0f);
  std::vector<Eigen::Vector3d> centres;
  for (const cv::Point2f& p : camera.undistortPixels(pixels))
    centres.emplace_back((p.x - camera.cx()) / camera.fx(), (p.y - camera.cy()) / camera.fy(), 1.0);
  return centres;
}

// Renders the blobs through the lens (as SceneSimulator::renderClean does) and returns the worst
// distance between a blob's intensity centroid and cv::projectPoints of its centre.
double worstBlobError(const PinholeCamera& camera, double* worstIdealShift = nullptr) {
  const DistortingLens lens(camera, kSupersample);
  render::SceneRenderer renderer;
  const std::vector<Eigen::Vector3d> centres = blobCentres(camera);
  // 20 px squares at 1 m (blob sigma 2.5 px at the image centre, less where the lens shrinks).
  const double side = 20.0 / camera.fx();
  for (const Eigen::Vector3d& c : centres)
    renderer.addMesh(
        test::texturedSquare(c, Eigen::Matrix3d::Identity(), side, test::blobTexture()));
  render::PinholeView view;
  view.K = render::supersampledK(lens.idealK(), kSupersample);
  view.imageSize =
      cv::Size(lens.idealSize().width * kSupersample, lens.idealSize().height * kSupersample);
  const cv::Mat image = lens.distortSupersampled(renderer.render(view, 1));
  EXPECT_EQ(image.size(), camera.imageSize());

  double worst = 0.0, shift = 0.0;
  for (const Eigen::Vector3d& c : centres) {
    std::vector<cv::Point2d> projected;
    cv::projectPoints(std::vector<cv::Point3d>{{c.x(), c.y(), c.z()}}, cv::Vec3d::all(0),
                      cv::Vec3d::all(0), camera.Kcv(), camera.distortion(), projected);
    const Eigen::Vector2d expected(projected[0].x, projected[0].y);
    const Eigen::Vector2d got = test::intensityCentroid(image, expected, 14);
    worst = std::max(worst, (got - expected).norm());
    shift = std::max(shift, (camera.project(c) - expected).norm());
  }
  if (worstIdealShift) *worstIdealShift = shift;
  return worst;
}

}  // namespace

// k1 = -0.3 (a wide webcam): every blob, those in the image corners included, lands where
// cv::projectPoints puts it. The error budget: cv::remap's 1/32-pixel interpolation grid on the
// 3x supersampled image (< 0.006 px), 8-bit rounding of the blob, and the lens's curvature across
// a blob of sigma <= 2.5 px (its second-order bias is below 0.01 px at the corners); 0.05 px
// holds all of it with room. Away from the centre the ideal projection misses by far more.
TEST_F(DistortingLensTest, BlobsLandAtTheDistortedProjectionIncludingTheCorners) {
  double idealMiss = 0.0;
  const double worst = worstBlobError(lensCamera({-0.3, 0.0, 0.0, 0.0}), &idealMiss);
  std::cout << "k1 = -0.3: worst blob error " << worst << " px\n";
  EXPECT_LT(worst, 0.05);
  // The ideal pinhole projection misses the corner blobs by tens of pixels: the check is not
  // vacuous.
  EXPECT_GT(idealMiss, 20.0);
}

TEST_F(DistortingLensTest, TangentialAndHigherRadialTermsToo) {
  const double worst = worstBlobError(lensCamera({-0.25, 0.08, 0.002, -0.0015, -0.01}));
  std::cout << "k1..k3, p1, p2: worst blob error " << worst << " px\n";
  EXPECT_LT(worst, 0.05);
}

TEST_F(DistortingLensTest, DepthIsRemappedToo) {
  const PinholeCamera camera = lensCamera({-0.3, 0.0, 0.0, 0.0});
  const DistortingLens lens(camera, kSupersample);
  // A wall at z = 2 m behind everything the camera sees: depth 2 at every output pixel.
  render::SceneRenderer renderer;
  renderer.addMesh(
      test::texturedSquare({0, 0, 2}, Eigen::Matrix3d::Identity(), 20.0, test::blobTexture()));
  render::PinholeView view;
  view.K = lens.idealK();
  view.imageSize = lens.idealSize();
  view.farPlane = 10.0;
  cv::Mat depth;
  renderer.render(view, 1, &depth);
  const cv::Mat distorted = lens.distortDepth(depth);
  ASSERT_EQ(distorted.size(), camera.imageSize());
  double lo = 0, hi = 0;
  cv::minMaxLoc(distorted, &lo, &hi);
  EXPECT_NEAR(lo, 2.0, 1e-3);
  EXPECT_NEAR(hi, 2.0, 1e-3);
}

// k1 = -0.3 alone at a 60-degree field of view: the image corners (normalised radius 0.72) lie
// beyond the lens's largest distorted radius (0.70), so no ray reaches them.
TEST(DistortingLens, RefusesALensThatFoldsBack) {
  const PinholeCamera wide = PinholeCamera::fromFieldOfView({640, 480}, 60.0);
  const PinholeCamera folded(wide.K(), wide.imageSize(), {-0.3, 0.0, 0.0, 0.0});
  try {
    DistortingLens lens(folded, kSupersample);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("folds back"), std::string::npos) << e.what();
  }
  EXPECT_THROW(DistortingLens(wide, kSupersample), Error);  // nothing to distort
}
