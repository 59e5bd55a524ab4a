#include "engine/reference/MarkerPoseEstimator.hpp"

#include <gtest/gtest.h>

#include <opencv2/aruco.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

namespace {

// A marker printed on white paper, imaged by `camera` at `pose` (world = marker frame). Rendered
// by an exact plane homography at 4x and area-averaged down, so edges are antialiased.
cv::Mat imageMarker(const MarkerSpec& spec, const PinholeCamera& camera, const RigidPose& pose) {
  const int s = 4, texPx = 800, borderPx = 200;  // quiet zone: 1/4 of the marker side each way
  cv::Mat marker;
  cv::aruco::drawMarker(cv::aruco::getPredefinedDictionary(spec.dictionaryEnum()), spec.id, texPx,
                        marker, 1);
  cv::Mat paper(texPx + 2 * borderPx, texPx + 2 * borderPx, CV_8UC1, cv::Scalar(235));
  marker.copyTo(paper(cv::Rect(borderPx, borderPx, texPx, texPx)));
  // Texture pixel (u, v) centre -> marker plane (x right, y up), metres.
  const double m = spec.sideMetres / texPx;
  Eigen::Matrix3d S;
  S << m, 0, -(borderPx + texPx / 2.0 - 0.5) * m, 0, -m, (borderPx + texPx / 2.0 - 0.5) * m, 0, 0,
      1;
  const PinholeCamera big = camera.scaled(s);
  Eigen::Matrix3d P;
  P << pose.rotation().col(0), pose.rotation().col(1), pose.translation();
  const Eigen::Matrix3d H = big.K() * P * S;
  cv::Matx33d Hcv;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Hcv(r, c) = H(r, c);
  cv::Mat warped, out;
  cv::warpPerspective(paper, warped, Hcv, big.imageSize(), cv::INTER_LINEAR, cv::BORDER_CONSTANT,
                      cv::Scalar(120));
  cv::resize(warped, out, camera.imageSize(), 0, 0, cv::INTER_AREA);
  return out;
}

// The marker's z axis points out of its printed face, towards a camera that looks at it: a
// camera facing the marker has its z axis opposite, so poses are built on a half turn about x.
RigidPose facingMarker(const Vector6d& x) {
  return RigidPose::fromVector6(x) *
         RigidPose::fromVector6((Vector6d() << 0, 0, 0, M_PI, 0, 0).finished());
}

std::string errorOf(const MarkerPoseEstimator& est, const cv::Mat& img) {
  return test::errorMessage([&] { est.estimate(img, "view.png"); });
}

}  // namespace

TEST(MarkerPoseEstimator, RecoversPoseOfRenderedMarker) {
  const MarkerSpec spec = MarkerSpec::parse("DICT_6X6_250:23:0.2");
  const PinholeCamera camera = PinholeCamera::fromFieldOfView({640, 480}, 60.0);
  const MarkerPoseEstimator est(spec, camera);
  // Oblique views (30-40 degrees off the marker normal) at 0.7-0.8 m.
  const Vector6d views[] = {(Vector6d() << 0.02, -0.01, 0.7, 0.6, 0.1, 0.05).finished(),
                            (Vector6d() << -0.05, 0.03, 0.75, -0.5, 0.45, -0.2).finished(),
                            (Vector6d() << 0.04, 0.02, 0.8, 0.4, -0.6, 1.0).finished()};
  for (const Vector6d& x : views) {
    const RigidPose truth = facingMarker(x);
    const MarkerPose got = est.estimate(imageMarker(spec, camera, truth), "view.png");
    // Issue 5 asks 2 mm / 0.1 degree for reference poses; a 20 cm marker seen obliquely from
    // 0.7-0.8 m is the set-up the simulator's references use, held to the same bound.
    EXPECT_LT(RigidPose::translationDistance(got.worldToCamera, truth), 0.002) << x.transpose();
    EXPECT_LT(RigidPose::rotationDistance(got.worldToCamera, truth) * 180 / M_PI, 0.1)
        << x.transpose();
    EXPECT_LT(got.reprojectionRmsPx, 0.3);
  }
}

TEST(MarkerPoseEstimator, ErrorsNameTheImageAndTheProblem) {
  const MarkerSpec spec = MarkerSpec::parse("DICT_6X6_250:23:0.12");
  const PinholeCamera camera = PinholeCamera::fromFieldOfView({640, 480}, 60.0);
  const MarkerPoseEstimator est(spec, camera);
  EXPECT_NE(errorOf(est, cv::Mat(480, 640, CV_8UC1, cv::Scalar(128)))
                .find("not found in image 'view.png'"),
            std::string::npos);
  EXPECT_NE(
      errorOf(est, cv::Mat(240, 320, CV_8UC1, cv::Scalar(128))).find("is 320x240 but the camera"),
      std::string::npos);
  EXPECT_NE(errorOf(est, cv::Mat()).find("empty or unreadable"), std::string::npos);
  // Another marker id in view: named in the message.
  const MarkerSpec other = MarkerSpec::parse("DICT_6X6_250:7:0.12");
  const cv::Mat img =
      imageMarker(other, camera, facingMarker((Vector6d() << 0, 0, 0.6, 0.4, 0, 0).finished()));
  EXPECT_NE(errorOf(est, img).find("markers seen: 7"), std::string::npos);
}

TEST(MarkerPoseEstimator, WorksOnRealPhotoOfPrintedMarkers) {
  const auto data = test::sharedDataDir();
  if (!data) GTEST_SKIP() << "../shared/data not present: real-data check skipped";
  const cv::Mat img = cv::imread((*data / "aruco-charuco" / "singlemarkersoriginal.jpg").string());
  ASSERT_FALSE(img.empty());
  // The tutorial's intrinsics (fx=fy=628.16) and distortion; its file has no image size keys.
  Eigen::Matrix3d K;
  K << 628.158, 0, 324.099, 0, 628.156, 260.908, 0, 0, 1;
  const PinholeCamera camera(K, img.size(), {0.0995485, -0.206384, 0.00754589, 0.00336531, 0});
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(img, cv::aruco::getPredefinedDictionary(cv::aruco::DICT_6X6_250),
                           corners, ids);
  ASSERT_FALSE(ids.empty());
  MarkerSpec spec;
  spec.id = ids[0];
  spec.sideMetres = 0.05;
  MarkerPoseParams params;
  params.ambiguityRatio = 1.0;  // real small markers may be nearly frontal; we test the fit only
  const MarkerPose pose =
      MarkerPoseEstimator(spec, camera, params).estimate(img, "singlemarkersoriginal.jpg");
  // Real corners with an approximate calibration: within one pixel.
  EXPECT_LT(pose.reprojectionRmsPx, 1.0);
  EXPECT_GT(pose.worldToCamera.translation().z(), 0.0);
}
