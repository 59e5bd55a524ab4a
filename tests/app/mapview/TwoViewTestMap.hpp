#pragma once
// A 320x240 two-reference map for map-picture tests: `points` random points 1-2 m in front of A,
// B 0.2 m to its right, each seen (and matched) in both views; images flat grey or, `textured`,
// uniform random noise.
#include <random>

#include "engine/reference/ReferenceMap.hpp"

namespace reftrack::test {

inline ReferenceMap twoViewTestMap(int points, unsigned seed, bool textured) {
  Eigen::Matrix3d K;
  K << 300, 0, 159.5, 0, 300, 119.5, 0, 0, 1;
  ReferenceMap map;
  map.camera = PinholeCamera(K, cv::Size(320, 240));
  map.T_A = RigidPose();
  map.T_B = RigidPose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.2, 0.0, 0.0));
  map.imageA = cv::Mat(240, 320, CV_8UC3, cv::Scalar(100, 100, 100));
  if (textured) cv::randu(map.imageA, 0, 255);
  map.imageB = map.imageA.clone();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.3, 0.3), z(1.0, 2.0);
  for (int i = 0; i < points; ++i) {
    const Eigen::Vector3d P(u(rng), u(rng), z(rng));
    const Eigen::Vector2d a = map.camera.project(P), b = map.camera.project(map.T_B * P);
    map.cornersA.push_back({cv::Point2f(static_cast<float>(a.x()), static_cast<float>(a.y())), 20});
    map.cornersB.push_back({cv::Point2f(static_cast<float>(b.x()), static_cast<float>(b.y())), 20});
    map.matches.push_back({i, i, P});
  }
  map.poseSource = "test";
  return map;
}

}  // namespace reftrack::test
