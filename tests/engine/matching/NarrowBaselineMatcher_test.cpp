#include "engine/matching/NarrowBaselineMatcher.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/features/SyntheticImages.hpp"

using namespace reftrack;

namespace {

// Fraction of matches whose second point lies within 1 px of H * first.
double correctFraction(const std::vector<CornerMatch>& m, const std::vector<Corner>& a,
                       const std::vector<Corner>& b, const cv::Matx33d& H) {
  int ok = 0;
  for (const auto& c : m) {
    const cv::Vec3d q = H * cv::Vec3d(a[c.first].position.x, a[c.first].position.y, 1);
    if (std::hypot(q[0] / q[2] - b[c.second].position.x, q[1] / q[2] - b[c.second].position.y) <
        1.0)
      ++ok;
  }
  return m.empty() ? 0.0 : static_cast<double>(ok) / m.size();
}

}  // namespace

TEST(NarrowBaselineMatcher, MatchesASmallShiftWithSymmetricCheck) {
  const cv::Mat a = test::texturedImage({320, 240}, 11);
  const cv::Matx33d H(1, 0, 6.3, 0, 1, -4.2, 0, 0, 1);
  const cv::Mat b = test::withNoise(test::warpedBy(a, H), 2.0, 1);
  CornerDetector det;
  const auto ca = det.detect(a), cb = det.detect(b);
  const auto m = NarrowBaselineMatcher().match(a, ca, b, cb);
  EXPECT_GT(m.size(), ca.size() * 6 / 10);
  EXPECT_GT(correctFraction(m, ca, cb, H), 0.95);
  for (const auto& c : m) EXPECT_GE(c.score, 0.8f);
  // Mutual best: no corner of either image is used twice.
  std::vector<int> used(cb.size(), 0);
  for (const auto& c : m) EXPECT_EQ(used[c.second]++, 0);
}

TEST(NarrowBaselineMatcher, PredictionGuidesBeyondTheSearchWindow) {
  const cv::Mat a = test::texturedImage({320, 240}, 12);
  const cv::Matx33d H(1, 0, 70, 0, 1, 45, 0, 0, 1);  // outside the +-40 x +-30 window
  const cv::Mat b = test::warpedBy(a, H);
  CornerDetector det;
  const auto ca = det.detect(a), cb = det.detect(b);
  NarrowBaselineMatcher matcher;
  const auto pa = positionsOf(ca), pb = positionsOf(cb);
  const auto A = NccPatches::square(a, pa, 5), B = NccPatches::square(b, pb, 5);
  const auto unguided = matcher.match(pa, A, pb, B, 40, 30);
  const auto guided = matcher.match(pa, A, pb, B, 4, 4, H);
  EXPECT_LT(correctFraction(unguided, ca, cb, H) * unguided.size(), 3.0);
  EXPECT_GT(guided.size(), 20u);
  EXPECT_GT(correctFraction(guided, ca, cb, H), 0.95);
}

TEST(NarrowBaselineMatcher, EmptyAndMismatchedInput) {
  NarrowBaselineMatcher matcher;
  NccPatches none(5);
  EXPECT_TRUE(matcher.match({}, none, {}, none, 10, 10).empty());
  EXPECT_THROW(matcher.match({{1, 1}}, none, {}, none, 10, 10), Error);
  CorrelationParams bad;
  bad.halfWindow = 0;
  EXPECT_THROW(NarrowBaselineMatcher{bad}, Error);
}
