#include "render/CameraProjection.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <opencv2/calib3d.hpp>

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

namespace {

// Distance from `p` to the polyline `line` (consecutive finite points).
double distanceToPolyline(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& line) {
  double best = INFINITY;
  for (std::size_t k = 1; k < line.size(); ++k) {
    const Eigen::Vector2d a = line[k - 1], ab = line[k] - a;
    const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

}  // namespace

// The desk clip's wide-angle lens (752x480, k1 = -0.297, k2 = 0.081): 3-D edges across the image
// (along the top, down the left side, a diagonal through the centre) 0.35 m away. Their pieces'
// polyline follows cv::projectPoints of 2001 points along each edge within 0.05 px (measured
// 0.0014 px: a 4 px step's chord stays within 0.01 px of the curve), where the straight chord
// between the ends misses it by tens of pixels (measured 31 px): the edges bend as the lens bends
// the video.
TEST(CameraProjection, SegmentThroughLensFollowsTheDistortedEdge) {
  Eigen::Matrix3d K;
  K << 420.50671, 0, 355.20830, 0, 420.61094, 250.33679, 0, 0, 1;
  const std::vector<double> lens = {-0.29668128, 0.08085691, 0.0, 0.0, 0.0};
  const cv::Matx33d cvK(K(0, 0), 0, K(0, 2), 0, K(1, 1), K(1, 2), 0, 0, 1);
  Eigen::Matrix4d pose = Eigen::Matrix4d::Identity();
  pose.topRightCorner<3, 1>() = Eigen::Vector3d(0.01, -0.02, 0.0);  // the world moved a little
  const double z = 0.35;
  const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> edges = {
      {{-0.30, -0.18, z}, {0.28, -0.19, z}},
      {{-0.31, -0.17, z}, {-0.30, 0.19, z}},
      {{-0.25, -0.15, z - 0.05}, {0.25, 0.18, z + 0.1}}};
  double worstPx = 0.0, largestChordPx = 0.0;
  for (const auto& [a, b] : edges) {
    const std::vector<Eigen::Vector2d> line = projectSegmentThroughLens(K, lens, pose, a, b, 0.01);
    ASSERT_GE(line.size(), 20u);
    std::vector<cv::Point3d> dense;
    for (int i = 0; i <= 2000; ++i) {
      const Eigen::Vector3d X = a + (b - a) * (i / 2000.0) + pose.topRightCorner<3, 1>();
      dense.emplace_back(X.x(), X.y(), X.z());
    }
    std::vector<cv::Point2d> truth;
    cv::projectPoints(dense, cv::Vec3d::all(0), cv::Vec3d::all(0), cvK, lens, truth);
    for (const cv::Point2d& q : truth) {
      const Eigen::Vector2d p(q.x, q.y);
      worstPx = std::max(worstPx, distanceToPolyline(p, line));
      largestChordPx = std::max(largestChordPx, distanceToPolyline(p, {line.front(), line.back()}));
    }
    // The ends are the lens's images of the segment's ends.
    EXPECT_LT((line.front() - Eigen::Vector2d(truth.front().x, truth.front().y)).norm(), 1e-6);
    EXPECT_LT((line.back() - Eigen::Vector2d(truth.back().x, truth.back().y)).norm(), 1e-6);
  }
  std::cout << "lens-drawn edges: worst " << worstPx << " px from the lens's image, the chords "
            << largestChordPx << " px\n";
  EXPECT_LT(worstPx, 0.05);
  EXPECT_GT(largestChordPx, 10.0);
}
