#pragma once
// A textured plane with exact geometry for the reference-preparation tests: world = the plane's
// frame (z = 0, z towards the cameras; as an ArUco marker's frame), a 1.6 m x 1.2 m random
// texture of polygons and discs at 1 mm per texel, optionally with an ArUco marker at the centre,
// imaged through exact plane homographies by a 640x480 pinhole camera (no distortion).
#include <Eigen/Geometry>
#include <opencv2/aruco.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/geometry/LookAt.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/MarkerSpec.hpp"

namespace reftrack::test {

class PlanarTestScene {
 public:
  static constexpr double kMetresPerTexel = 0.001;
  static constexpr int kTextureWidth = 1600, kTextureHeight = 1200;

  explicit PlanarTestScene(const MarkerSpec* marker = nullptr, unsigned seed = 3) {
    Eigen::Matrix3d K;
    K << 600, 0, 319.5, 0, 600, 239.5, 0, 0, 1;
    camera = PinholeCamera(K, cv::Size(640, 480));
    texture = cv::Mat(kTextureHeight, kTextureWidth, CV_8UC1, cv::Scalar(128));
    cv::RNG rng(seed);
    for (int i = 0; i < 2500; ++i) {
      const cv::Point c(rng.uniform(0, kTextureWidth), rng.uniform(0, kTextureHeight));
      const int grey = rng.uniform(0, 256), r = rng.uniform(6, 40);
      if (i % 3 == 0) {
        cv::circle(texture, c, r, cv::Scalar(grey), cv::FILLED, cv::LINE_AA);
      } else {
        std::vector<cv::Point> poly;
        for (int k = 0; k < 3 + i % 3; ++k)
          poly.emplace_back(c.x + rng.uniform(-r, r), c.y + rng.uniform(-r, r));
        cv::fillConvexPoly(texture, poly, cv::Scalar(grey), cv::LINE_AA);
      }
    }
    cv::GaussianBlur(texture, texture, cv::Size(0, 0), 1.0);  // band-limit the 1 mm texels
    if (marker) {
      const int side = static_cast<int>(std::lround(marker->sideMetres / kMetresPerTexel));
      const int border = side / 5;
      cv::Rect white((kTextureWidth - side) / 2 - border, (kTextureHeight - side) / 2 - border,
                     side + 2 * border, side + 2 * border);
      texture(white).setTo(cv::Scalar(255));
      cv::Mat code;
      cv::aruco::drawMarker(cv::aruco::getPredefinedDictionary(marker->dictionaryEnum()),
                            marker->id, side, code, 1);
      code.copyTo(
          texture(cv::Rect((kTextureWidth - side) / 2, (kTextureHeight - side) / 2, side, side)));
    }
  }

  // World->camera pose of a camera at `eye` looking at `target`, image up = world +y.
  static RigidPose lookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
    return lookAtPose(eye, target, Eigen::Vector3d::UnitY());
  }

  // Texture pixel (u, v) (centres at integers) -> world (x, y, 0): x right, y up.
  Eigen::Matrix3d textureToPlane() const {
    const double s = kMetresPerTexel, u0 = (kTextureWidth - 1) / 2.0,
                 v0 = (kTextureHeight - 1) / 2.0;
    Eigen::Matrix3d S;
    S << s, 0, -s * u0, 0, -s, s * v0, 0, 0, 1;
    return S;
  }
  // Plane (x, y, 1) -> image pixel for a world->camera pose: K [r1 r2 t].
  Eigen::Matrix3d planeToImage(const RigidPose& T) const {
    Eigen::Matrix3d M;
    M.col(0) = T.rotation().col(0);
    M.col(1) = T.rotation().col(1);
    M.col(2) = T.translation();
    return camera.K() * M;
  }

  // The view of the plane through T, with Gaussian noise of `noiseSd` grey levels (fixed seed).
  cv::Mat render(const RigidPose& T, double noiseSd = 1.0) const {
    const Eigen::Matrix3d H = planeToImage(T) * textureToPlane();
    cv::Matx33d Hcv;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) Hcv(r, c) = H(r, c);
    cv::Mat image;
    cv::warpPerspective(texture, image, Hcv, camera.imageSize(), cv::INTER_LINEAR,
                        cv::BORDER_CONSTANT, cv::Scalar(60));
    cv::Mat noise(image.size(), CV_32F);
    cv::RNG rng(11);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, noiseSd);
    cv::Mat out;
    image.convertTo(out, CV_32F);
    out += noise;
    out.convertTo(out, CV_8U);
    return out;
  }

  // Exact A -> B pixel map of the plane (a homography).
  Eigen::Matrix3d homographyAtoB(const RigidPose& T_A, const RigidPose& T_B) const {
    return planeToImage(T_B) * planeToImage(T_A).inverse();
  }

  PinholeCamera camera;
  cv::Mat texture;  // CV_8UC1
};

}  // namespace reftrack::test
