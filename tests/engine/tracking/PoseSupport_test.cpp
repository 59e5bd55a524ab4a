#include "engine/tracking/PoseSupport.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

namespace reftrack {
namespace {

struct Scene {
  PinholeCamera camera{(Eigen::Matrix3d() << 520, 0, 319.5, 0, 520, 239.5, 0, 0, 1).finished(),
                       cv::Size(640, 480)};
  RigidPose truth =
      RigidPose::fromVector6((Vector6d() << 0.05, -0.02, 0.1, 0.02, -0.05, 0.01).finished());
  std::vector<Eigen::Vector3d> points;
  explicit Scene(int n) {
    cv::RNG rng(5);
    for (int i = 0; i < n; ++i)
      points.emplace_back(rng.uniform(-0.5, 0.5), rng.uniform(-0.4, 0.4), rng.uniform(1.0, 2.0));
  }
  // Noisy observations and the least-squares pose from them (OpenCV's iterative PnP).
  std::pair<std::vector<ThreeViewMatch>, RigidPose> observe(double noisePx, cv::RNG& rng) const {
    std::vector<ThreeViewMatch> m;
    std::vector<cv::Point3d> object;
    std::vector<cv::Point2d> image;
    for (const Eigen::Vector3d& P : points) {
      const Eigen::Vector2d p =
          camera.project(truth * P) + Eigen::Vector2d(rng.gaussian(noisePx), rng.gaussian(noisePx));
      m.push_back({P, p, 1.0});
      object.emplace_back(P.x(), P.y(), P.z());
      image.emplace_back(p.x(), p.y());
    }
    const Vector6d x0 = truth.toVector6();
    cv::Vec3d t(x0[0], x0[1], x0[2]), r(x0[3], x0[4], x0[5]);
    cv::solvePnP(object, image, camera.Kcv(), cv::noArray(), r, t, true, cv::SOLVEPNP_ITERATIVE);
    return {m,
            RigidPose::fromVector6((Vector6d() << t[0], t[1], t[2], r[0], r[1], r[2]).finished())};
  }
};

// With N points and isotropic noise SD sigma, the least-squares pose moves the reprojections by
// sigma * sqrt(3 / N) per axis on average (6 parameters spread over 2N coordinates). The support
// SD computed at each estimate must agree with that and with the scatter actually observed over
// 200 trials: 15% covers the sampling error of s^2 from 2N - 6 = 114 residual degrees of freedom
// (~7% SD) and of the 200-trial scatter (~3%).
TEST(PoseSupport, PredictsTheReprojectionScatterOfTheLeastSquaresPose) {
  const Scene scene(60);
  const double sigma = 0.5;
  const double expected = sigma * std::sqrt(3.0 / 60.0);
  cv::RNG rng(11);
  double predicted = 0.0, scatter = 0.0;
  const int trials = 200;
  for (int t = 0; t < trials; ++t) {
    const auto [matches, estimate] = scene.observe(sigma, rng);
    const std::optional<double> sd = reprojectionSupportSdPx(scene.camera, estimate, matches);
    ASSERT_TRUE(sd.has_value());
    EXPECT_NEAR(*sd, expected, 0.3 * expected);  // one trial: s^2 alone varies ~13% (SD)
    predicted += *sd * *sd;
    for (const Eigen::Vector3d& P : scene.points)
      scatter += (scene.camera.project(estimate * P) - scene.camera.project(scene.truth * P))
                     .squaredNorm() /
                 2.0;
  }
  predicted = std::sqrt(predicted / trials);
  scatter = std::sqrt(scatter / (trials * static_cast<double>(scene.points.size())));
  EXPECT_NEAR(predicted, expected, 0.15 * expected);
  EXPECT_NEAR(scatter, expected, 0.15 * expected);
}

// Fewer points and larger residuals mean weaker support; under 4 points there is none.
TEST(PoseSupport, GrowsWithNoiseAndFewerPointsAndNeedsFourPoints) {
  cv::RNG rng(3);
  const Scene many(80), few(12);
  const auto sdOf = [&](const Scene& s, double noise) {
    const auto [m, estimate] = s.observe(noise, rng);
    return reprojectionSupportSdPx(s.camera, estimate, m).value();
  };
  EXPECT_GT(sdOf(many, 2.0), 2.5 * sdOf(many, 0.5));  // SD proportional to the noise: ~4x
  EXPECT_GT(sdOf(few, 0.5), 1.5 * sdOf(many, 0.5));   // sqrt(80 / 12) ~ 2.6x
  std::vector<ThreeViewMatch> three;
  for (int i = 0; i < 3; ++i)
    three.push_back({many.points[static_cast<std::size_t>(i)],
                     many.camera.project(many.truth * many.points[static_cast<std::size_t>(i)]),
                     1.0});
  EXPECT_FALSE(reprojectionSupportSdPx(many.camera, many.truth, three).has_value());
}

}  // namespace
}  // namespace reftrack
