#pragma once
// CornerWorld: an exact non-planar synthetic scene for the relocalisation tests — the inside of a
// room corner (floor z = 0 and walls x = 0, y = 0, each 1 m square, each with its own texture),
// seen by a pinhole camera from anywhere in front of all three. Rendered with a z-buffer at twice
// the resolution and averaged down (no aliasing), with sensor noise: the poses are exact.
#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/tracking/TrackingTestImages.hpp"

namespace reftrack::test {

struct CornerWorld {
  struct Plane {
    Eigen::Vector3d origin, u, v;  // texture pixel (a, b) -> origin + (a u + b v) * metres/texel
    cv::Mat texture;
  };
  static constexpr double kPlaneSizeM = 1.0;
  static constexpr int kTexels = 1024;
  cv::Size size{640, 480};
  Eigen::Matrix3d K;
  std::vector<Plane> planes;

  // textureSeed: another seed gives another scene of the same shape (a "wrong scene").
  explicit CornerWorld(int textureSeed = 1) {
    K << 520, 0, 319.5, 0, 520, 239.5, 0, 0, 1;
    const Eigen::Vector3d o = Eigen::Vector3d::Zero(), x = Eigen::Vector3d::UnitX(),
                          y = Eigen::Vector3d::UnitY(), z = Eigen::Vector3d::UnitZ();
    planes = {{o, x, y, texturedImage({kTexels, kTexels}, 100 * textureSeed + 1)},
              {o, y, z, texturedImage({kTexels, kTexels}, 100 * textureSeed + 2)},
              {o, x, z, texturedImage({kTexels, kTexels}, 100 * textureSeed + 3)}};
  }

  PinholeCamera camera() const { return PinholeCamera(K, size); }
  static Eigen::Vector3d centre() { return Eigen::Vector3d(0.35, 0.35, 0.35); }

  // World->camera pose of a camera at `eye` looking at `target` (world z up in the image when
  // roll = 0), rolled by `rollDeg` about its optical axis.
  static RigidPose lookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                          double rollDeg) {
    const Eigen::Vector3d f = (target - eye).normalized();
    Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
    if (std::abs(f.dot(up)) > 0.99) up = Eigen::Vector3d::UnitX();
    const Eigen::Vector3d r = f.cross(up).normalized();
    const Eigen::Vector3d d = f.cross(r);
    Eigen::Matrix3d R;
    R.row(0) = r.transpose();
    R.row(1) = d.transpose();
    R.row(2) = f.transpose();
    R = Eigen::AngleAxisd(rollDeg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R;
    return RigidPose(R, -R * eye);
  }

  cv::Mat render(const RigidPose& T, int noiseSeed) const {
    const int s = 2;  // supersampling
    const cv::Size big(size.width * s, size.height * s);
    Eigen::Matrix3d K2 = K;
    K2.row(0) *= s;
    K2.row(1) *= s;
    K2(0, 2) += 0.5 * (s - 1);  // pixel centres at integers in both images
    K2(1, 2) += 0.5 * (s - 1);
    cv::Mat xs(big, CV_32F), ys(big, CV_32F);
    for (int r = 0; r < big.height; ++r)
      for (int c = 0; c < big.width; ++c) {
        xs.at<float>(r, c) = static_cast<float>(c);
        ys.at<float>(r, c) = static_cast<float>(r);
      }
    cv::Mat image(big, CV_8U, cv::Scalar(128)), inverseDepth(big, CV_32F, cv::Scalar(0));
    const double m = kPlaneSizeM / kTexels;
    for (const Plane& p : planes) {
      Eigen::Matrix3d H;
      H.col(0) = K2 * (T.rotation() * p.u * m);
      H.col(1) = K2 * (T.rotation() * p.v * m);
      H.col(2) = K2 * (T * p.origin);
      cv::Matx33d Hcv;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) Hcv(r, c) = H(r, c);
      cv::Mat warpedTexture, mask;
      cv::warpPerspective(p.texture, warpedTexture, cv::Mat(Hcv), big, cv::INTER_LINEAR,
                          cv::BORDER_CONSTANT, cv::Scalar(0));
      cv::warpPerspective(cv::Mat(p.texture.size(), CV_8U, cv::Scalar(255)), mask, cv::Mat(Hcv),
                          big, cv::INTER_NEAREST, cv::BORDER_CONSTANT, cv::Scalar(0));
      // 1/z of the plane at each pixel: n_c . K^-1 (x, y, 1) / d_c (affine in the pixel).
      const Eigen::Vector3d nc = T.rotation() * p.u.cross(p.v);
      const double dc = nc.dot(T * p.origin);
      if (std::abs(dc) < 1e-9) continue;  // seen edge-on
      const Eigen::Vector3d a = K2.inverse().transpose() * nc / dc;
      cv::Mat invZ = xs * a.x() + ys * a.y() + a.z();
      cv::Mat nearer = (invZ > inverseDepth) & (invZ > 0) & (mask > 0);
      warpedTexture.copyTo(image, nearer);
      invZ.copyTo(inverseDepth, nearer);
    }
    cv::Mat small;
    cv::resize(image, small, size, 0, 0, cv::INTER_AREA);
    cv::Mat noise(size, CV_16S);
    cv::RNG rng(static_cast<std::uint64_t>(noiseSeed));
    rng.fill(noise, cv::RNG::NORMAL, 0, 2.0);
    cv::Mat out;
    cv::add(small, noise, out, cv::noArray(), CV_8U);
    return out;
  }

  // n reference poses around the corner, at `distance` from centre(): azimuths 20..70 degrees,
  // elevations 30 and 55 degrees, alternating.
  static std::vector<RigidPose> referencePoses(int n, double distance) {
    std::vector<RigidPose> poses;
    for (int i = 0; i < n; ++i) {
      const double az = (20.0 + 50.0 * i / std::max(1, n - 1)) * M_PI / 180.0;
      const double el = (i % 2 == 0 ? 30.0 : 55.0) * M_PI / 180.0;
      const Eigen::Vector3d dir(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                std::sin(el));
      poses.push_back(lookAt(centre() + distance * dir, centre(), 0.0));
    }
    return poses;
  }
};

}  // namespace reftrack::test
