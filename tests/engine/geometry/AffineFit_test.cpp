#include "engine/geometry/AffineFit.hpp"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace reftrack {
namespace {

using Pairs = std::vector<std::pair<cv::Point2d, cv::Point2d>>;

AffineFit fit(const Pairs& pairs, cv::Matx33d& A) {
  return fitAffine(
      static_cast<int>(pairs.size()), [&](int j) { return pairs[static_cast<std::size_t>(j)]; }, A);
}

// Pairs related by an exact affine map give that map back (to rounding: 1e-9 of unit-sized
// coefficients), whatever the offset of the points from the origin (centring keeps it exact).
TEST(AffineFit, RecoversAnExactAffineMap) {
  const cv::Matx33d truth(1.2, -0.3, 15.0, 0.25, 0.9, -7.5, 0, 0, 1);
  Pairs pairs;
  for (const cv::Point2d p : {cv::Point2d(400, 300), cv::Point2d(410, 302), cv::Point2d(403, 315),
                              cv::Point2d(396, 309), cv::Point2d(407, 296)}) {
    const cv::Vec3d q = truth * cv::Vec3d(p.x, p.y, 1.0);
    pairs.emplace_back(p, cv::Point2d(q[0], q[1]));
  }
  cv::Matx33d A;
  ASSERT_EQ(fit(pairs, A), AffineFit::Fitted);
  EXPECT_LT(cv::norm(A - truth, cv::NORM_INF), 1e-9);
}

TEST(AffineFit, NamesWhyNoMapIsFitted) {
  cv::Matx33d A;
  EXPECT_EQ(fit({{{0, 0}, {1, 1}}, {{5, 0}, {6, 1}}}, A), AffineFit::TooFew);
  // On one line (spread across it 0 px), and 0.4 px off it: more pairs are needed.
  EXPECT_EQ(fit({{{0, 0}, {0, 0}}, {{5, 5}, {5, 5}}, {{10, 10}, {10, 10}}}, A),
            AffineFit::Collinear);
  EXPECT_EQ(fit({{{0, 0}, {0, 0}}, {{5, 5.4}, {5, 5}}, {{10, 10}, {10, 10}}}, A),
            AffineFit::Collinear);
  // Spread out, but the destinations all but coincide (|det| < 1e-3) or blow up (> 1e3).
  EXPECT_EQ(fit({{{0, 0}, {3, 3}}, {{20, 0}, {3, 3.001}}, {{0, 20}, {3.001, 3}}}, A),
            AffineFit::Degenerate);
  EXPECT_EQ(fit({{{0, 0}, {0, 0}}, {{20, 0}, {1e5, 0}}, {{0, 20}, {0, 1e5}}}, A),
            AffineFit::Degenerate);
}

}  // namespace
}  // namespace reftrack
