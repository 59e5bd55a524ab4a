#include "engine/relocalisation/EpipolarKeypointMatcher.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "engine/core/Error.hpp"
#include "engine/geometry/FundamentalMatrix.hpp"
#include "engine/geometry/RigidPose.hpp"

using namespace reftrack;

namespace {

struct TwoViews {
  Eigen::Matrix3d K;
  RigidPose Tij;  // view i -> view j
  Eigen::Matrix3d F;
  TwoViews() {
    K << 500, 0, 320, 0, 500, 240, 0, 0, 1;
    Vector6d x;
    x << -0.1, 0.01, 0.02, 0.01, 0.05, -0.02;
    Tij = RigidPose::fromVector6(x);
    F = fundamentalMatrix(K, Tij);
  }
  cv::Point2f project(const Eigen::Vector3d& X) const {
    const Eigen::Vector3d p = K * X;
    return {static_cast<float>(p.x() / p.z()), static_cast<float>(p.y() / p.z())};
  }
};

cv::Mat randomDescriptors(int rows, std::mt19937& rng) {
  cv::Mat d(rows, 32, CV_8U);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < 32; ++c) d.at<uchar>(r, c) = static_cast<uchar>(byte(rng));
  return d;
}

}  // namespace

// Repeated texture: every keypoint of i has a twin descriptor in j, but off its epipolar line;
// a whole-image ratio test rejects all of them, the epipolar-guided match finds each true one.
TEST(EpipolarKeypointMatcher, MatchesRepeatedDescriptorsAlongTheirLines) {
  const TwoViews v;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.4, 0.4), z(1.5, 3.0);
  const int n = 40;
  std::vector<cv::Point2f> pi, pj;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d X(u(rng), u(rng), z(rng));
    pi.push_back(v.project(X));
    pj.push_back(v.project(v.Tij * X));
  }
  const cv::Mat di = randomDescriptors(n, rng);
  cv::Mat dj = di.clone();
  // The twins: j also holds every descriptor once more at a point 60 px off (not on the line:
  // the lines here are nearly horizontal, the twins are shifted vertically).
  std::vector<cv::Point2f> pj2 = pj;
  cv::Mat dj2 = dj.clone();
  for (int k = 0; k < n; ++k) {
    pj2.push_back(pj[static_cast<std::size_t>(k)] + cv::Point2f(0, 60));
    dj2.push_back(di.row(k));
  }
  const std::vector<double> ti(pi.size(), 1.0), tj(pj2.size(), 1.0);
  const auto matches = matchAlongEpipolarLines(v.F, pi, ti, di, pj2, tj, dj2, cv::NORM_HAMMING);
  EXPECT_EQ(static_cast<int>(matches.size()), n);
  for (const auto& [a, b] : matches) EXPECT_EQ(a, b);
}

// Two look-alikes on the same line are ambiguous (ratio test among the candidates), and a lone
// candidate whose descriptor differs too much is no match.
TEST(EpipolarKeypointMatcher, RefusesAmbiguousAndDissimilarCandidates) {
  const TwoViews v;
  std::mt19937 rng(5);
  const Eigen::Vector3d X(0.1, -0.05, 2.0);
  const std::vector<cv::Point2f> pi = {v.project(X)};
  const cv::Point2f onLine = v.project(v.Tij * X);
  const Eigen::Vector3d X2 = 1.4 * X;  // same ray in i: projects onto the same line in j
  const std::vector<cv::Point2f> pj = {onLine, v.project(v.Tij * X2)};
  const cv::Mat di = randomDescriptors(1, rng);
  cv::Mat dj;
  dj.push_back(di.row(0));
  dj.push_back(di.row(0));
  const std::vector<double> ti = {1.0}, tj = {1.0, 1.0};
  EXPECT_TRUE(matchAlongEpipolarLines(v.F, pi, ti, di, pj, tj, dj, cv::NORM_HAMMING).empty());
  // One candidate only, but a random descriptor (~128 of 256 bits differ > 25%).
  const std::vector<cv::Point2f> one = {onLine};
  const std::vector<double> t1 = {1.0};
  EXPECT_TRUE(
      matchAlongEpipolarLines(v.F, pi, ti, di, one, t1, randomDescriptors(1, rng), cv::NORM_HAMMING)
          .empty());
  EXPECT_EQ(matchAlongEpipolarLines(v.F, pi, ti, di, one, t1, di, cv::NORM_HAMMING).size(), 1u);
  EXPECT_THROW(matchAlongEpipolarLines(v.F, pi, {}, di, one, t1, di, cv::NORM_HAMMING), Error);
}
