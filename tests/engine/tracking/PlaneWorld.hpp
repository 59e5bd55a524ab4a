#pragma once
// PlaneWorld: an exact synthetic scene for the tracker tests — see below.
#include <opencv2/imgproc.hpp>

#include "TrackingTestImages.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/reference/ReferenceMap.hpp"

namespace reftrack::test {

// A textured, tilted plane seen by reference cameras A and B and by a moving camera: every view
// is an exact plane-induced homography of one large texture, so ground truth is exact (poses and
// 3D points), with sensor noise added. Plane in camera A's frame: n^T X = d.
struct PlaneWorld {
  cv::Size size{640, 480};
  Eigen::Matrix3d K;
  Eigen::Vector3d n = Eigen::Vector3d(0.0, -0.25, 1.0).normalized();
  double d = 1.0;
  cv::Mat texture;  // 1920x1440, texture pixel (u, v) = A pixel (u - 640, v - 480)
  RigidPose T_A, T_AB;

  PlaneWorld() {
    K << 520, 0, 319.5, 0, 520, 239.5, 0, 0, 1;
    texture = texturedImage({1920, 1440}, 21);
    T_A = RigidPose::fromVector6((Vector6d() << 0.1, -0.05, 0.9, 2.6, 0.1, -0.05).finished());
    T_AB = RigidPose::fromVector6((Vector6d() << -0.22, 0.01, 0.03, 0.0, 0.12, 0.01).finished());
  }
  cv::Matx33d homography(const RigidPose& T_AC) const {  // A pixels -> C pixels
    const Eigen::Matrix3d H =
        K * (T_AC.rotation() + T_AC.translation() * n.transpose() / d) * K.inverse();
    cv::Matx33d out;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out(r, c) = H(r, c);
    return out;
  }
  cv::Mat render(const RigidPose& T_AC, int noiseSeed) const {
    const cv::Matx33d offset(1, 0, -640, 0, 1, -480, 0, 0, 1);
    cv::Mat img;
    cv::warpPerspective(texture, img, cv::Mat(homography(T_AC) * offset), size, cv::INTER_AREA,
                        cv::BORDER_REPLICATE);
    cv::Mat noise(size, CV_16S);
    cv::RNG rng(static_cast<std::uint64_t>(noiseSeed));
    rng.fill(noise, cv::RNG::NORMAL, 0, 2.0);
    cv::Mat out;
    cv::add(img, noise, out, cv::noArray(), CV_8U);
    return out;
  }
  Eigen::Vector3d backProject(cv::Point2f pA) const {  // ray through A pixel hits the plane
    const Eigen::Vector3d ray = K.inverse() * Eigen::Vector3d(pA.x, pA.y, 1.0);
    return ray * (d / n.dot(ray));
  }

  ReferenceMap map() const {
    ReferenceMap m;
    m.camera = PinholeCamera(K, size);
    m.T_A = T_A;
    m.T_B = T_AB * T_A;
    m.imageA = render(RigidPose(), 1);
    m.imageB = render(T_AB, 2);
    CornerParams cp;
    cp.countAt320x240 = 200;
    cp.detectAtPaperScale = false;
    const CornerDetector detector(cp);
    for (const Corner& c : detector.detect(m.imageA))
      m.cornersA.push_back({c.position, c.contrast});
    for (const Corner& c : detector.detect(m.imageB))
      m.cornersB.push_back({c.position, c.contrast});
    const cv::Matx33d H = homography(T_AB);
    for (int a = 0; a < static_cast<int>(m.cornersA.size()); ++a) {
      const cv::Point2d pb = applyH(H, m.cornersA[static_cast<std::size_t>(a)].pixel);
      for (int b = 0; b < static_cast<int>(m.cornersB.size()); ++b)
        if (cv::norm(cv::Point2d(m.cornersB[static_cast<std::size_t>(b)].pixel) - pb) < 1.0) {
          m.matches.push_back({a, b, backProject(m.cornersA[static_cast<std::size_t>(a)].pixel)});
          break;
        }
    }
    m.poseSource = "synthetic plane";
    return m;
  }
};

inline RigidPose pathPose(int k) {  // camera A -> frame k: smooth sideways move with rotation
  const double s = k / 40.0;
  Vector6d x;
  x << 0.12 * s, -0.04 * s, 0.05 * s, 0.03 * s, -0.10 * s, 0.02 * s;
  return RigidPose::fromVector6(x);
}

}  // namespace reftrack::test
