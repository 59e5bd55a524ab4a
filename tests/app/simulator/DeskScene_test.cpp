#include "app/simulator/DeskScene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/aruco.hpp>

#include "engine/geometry/LookAt.hpp"
#include "engine/geometry/PinholeCamera.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

const DeskScene& scene() {
  static const DeskScene s = buildDeskScene();
  return s;
}

// World position of texture coordinate (u, v) in texels (pixel-centre convention) of a quad
// mesh whose vertices 0, 1, 3 carry uv (0,0), (1,0), (0,1).
Eigen::Vector3d onQuad(const render::TexturedMesh& m, double u, double v) {
  const Eigen::Vector3d p0 = m.positions[0].cast<double>();
  const Eigen::Vector3d right = m.positions[1].cast<double>() - p0;
  const Eigen::Vector3d down = m.positions[3].cast<double>() - p0;
  return p0 + (u + 0.5) / m.texture.cols * right + (v + 0.5) / m.texture.rows * down;
}

}  // namespace

TEST(DeskScene, MeshesAreWellFormed) {
  ASSERT_GT(scene().meshes.size(), 50u);
  for (const render::TexturedMesh& m : scene().meshes) {
    ASSERT_EQ(m.positions.size(), m.uvs.size());
    ASSERT_EQ(m.indices.size() % 3, 0u);
    for (std::uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
    ASSERT_EQ(m.texture.type(), CV_8UC3);
    // Texel size: <= 1.3 mm on the walls (seen from >= 1.3 m), <= 0.53 mm on the desk and
    // boxes: >= 2 texels per pixel down to 0.6 m at 640 px / 60 deg (1.04 mm pixels there).
    const double side = (m.positions[1] - m.positions[0]).norm();
    const double texel = side / m.texture.cols;
    const auto onWall = [](const Eigen::Vector3f& p) {
      return std::abs(p.y() - 1.0f) < 1e-6f || std::abs(std::abs(p.x()) - 1.0f) < 1e-6f;
    };
    const bool wall = std::all_of(m.positions.begin(), m.positions.end(), onWall);
    EXPECT_LE(texel, wall ? 0.0013 : 0.00053);
  }
}

TEST(DeskScene, MarkerIsPrintedExactlyAtItsWorldCorners) {
  const MarkerSpec& marker = scene().marker;
  EXPECT_EQ(marker.toString(), "DICT_6X6_250:23:0.2");
  const auto dict = cv::aruco::getPredefinedDictionary(marker.dictionaryEnum());
  auto params = cv::aruco::DetectorParameters::create();
  params->cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
  int found = 0;
  for (const render::TexturedMesh& m : scene().meshes) {
    std::vector<std::vector<cv::Point2f>> corners;
    std::vector<int> ids;
    cv::aruco::detectMarkers(m.texture, dict, corners, ids, params);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      ASSERT_EQ(ids[i], marker.id);
      ++found;
      const auto truth = marker.cornersWorld();
      for (int c = 0; c < 4; ++c) {
        // Detected in the texture seen head-on; the corner lies on a texel edge, so sub-pixel
        // refinement finds it within ~0.2 texel = 0.1 mm.
        const Eigen::Vector3d world = onQuad(m, corners[i][c].x, corners[i][c].y);
        EXPECT_LT((world - truth[c]).norm(), 1e-4) << "corner " << c;
      }
    }
  }
  EXPECT_EQ(found, 1);
}

TEST(DeskScene, ReferenceViewsSeeTheMarkerObliquely) {
  const PinholeCamera cam = PinholeCamera::fromFieldOfView({640, 480}, 60.0);
  const Eigen::Vector3d a = scene().referenceEyeA, b = scene().referenceEyeB;
  EXPECT_NEAR((b - a).norm(), 0.25, 1e-12);
  EXPECT_GT(a.norm(), 0.8);
  EXPECT_LT(a.norm(), 1.0);
  const double offNormal = std::acos(a.normalized().z()) * 180.0 / M_PI;
  EXPECT_GT(offNormal, 30.0);
  EXPECT_LT(offNormal, 40.0);
  for (const Eigen::Vector3d& eye : {a, b}) {
    const RigidPose pose = lookAtPose(eye, scene().contentCentre);
    for (const Eigen::Vector3d& corner : scene().marker.cornersWorld()) {
      const Eigen::Vector2d p = cam.project(pose, corner);
      EXPECT_GT(p.x(), 40);
      EXPECT_LT(p.x(), 600);
      EXPECT_GT(p.y(), 40);
      EXPECT_LT(p.y(), 440);
    }
  }
}
