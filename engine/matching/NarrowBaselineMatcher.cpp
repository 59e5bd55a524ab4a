#include "engine/matching/NarrowBaselineMatcher.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

NarrowBaselineMatcher::NarrowBaselineMatcher(CorrelationParams params) : params_(params) {
  params_.check();
}

std::vector<CornerMatch> NarrowBaselineMatcher::match(
    const std::vector<cv::Point2f>& first, const NccPatches& firstPatches,
    const std::vector<cv::Point2f>& second, const NccPatches& secondPatches, double halfWidth,
    double halfHeight, const std::optional<cv::Matx33d>& firstToSecond) const {
  if (firstPatches.size() != static_cast<int>(first.size()) ||
      secondPatches.size() != static_cast<int>(second.size()))
    throw Error("narrow-baseline matching: one NCC window per point is required");
  const int n1 = static_cast<int>(first.size()), n2 = static_cast<int>(second.size());
  if (n1 == 0 || n2 == 0) return {};

  // Second points sorted by x, so each search window is a binary-searched x range.
  std::vector<int> order(static_cast<size_t>(n2));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return second[a].x < second[b].x; });
  std::vector<float> xs(static_cast<size_t>(n2));
  for (int k = 0; k < n2; ++k) xs[static_cast<size_t>(k)] = second[order[k]].x;

  const float minScore = static_cast<float>(params_.minScore);
  std::vector<int> best1(static_cast<size_t>(n1), -1), best2(static_cast<size_t>(n2), -1);
  std::vector<float> score1(static_cast<size_t>(n1), -2.0f), score2(static_cast<size_t>(n2), -2.0f);
  for (int i = 0; i < n1; ++i) {
    if (!firstPatches.valid(i)) continue;
    cv::Point2d p(first[i].x, first[i].y);
    if (firstToSecond) {
      const cv::Matx33d& H = *firstToSecond;
      const double w = H(2, 0) * p.x + H(2, 1) * p.y + H(2, 2);
      if (!(std::abs(w) > 1e-12)) continue;
      p = cv::Point2d((H(0, 0) * p.x + H(0, 1) * p.y + H(0, 2)) / w,
                      (H(1, 0) * p.x + H(1, 1) * p.y + H(1, 2)) / w);
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
    }
    const auto lo = std::lower_bound(xs.begin(), xs.end(), static_cast<float>(p.x - halfWidth));
    const auto hi = std::upper_bound(xs.begin(), xs.end(), static_cast<float>(p.x + halfWidth));
    for (auto it = lo; it != hi; ++it) {
      const int j = order[static_cast<size_t>(it - xs.begin())];
      if (std::abs(second[j].y - p.y) > halfHeight) continue;
      const float s = firstPatches.score(i, secondPatches, j);
      if (s > score1[static_cast<size_t>(i)]) {
        score1[static_cast<size_t>(i)] = s;
        best1[static_cast<size_t>(i)] = j;
      }
      if (s > score2[static_cast<size_t>(j)]) {
        score2[static_cast<size_t>(j)] = s;
        best2[static_cast<size_t>(j)] = i;
      }
    }
  }
  std::vector<CornerMatch> matches;
  for (int i = 0; i < n1; ++i) {
    const int j = best1[static_cast<size_t>(i)];
    if (j < 0 || score1[static_cast<size_t>(i)] < minScore) continue;
    if (params_.symmetricCheck && best2[static_cast<size_t>(j)] != i) continue;
    matches.push_back({i, j, score1[static_cast<size_t>(i)]});
  }
  return matches;
}

std::vector<CornerMatch> NarrowBaselineMatcher::match(const cv::Mat& gray1,
                                                      const std::vector<Corner>& corners1,
                                                      const cv::Mat& gray2,
                                                      const std::vector<Corner>& corners2) const {
  const std::vector<cv::Point2f> p1 = positionsOf(corners1), p2 = positionsOf(corners2);
  const double s = resolutionScale(gray2.size());
  return match(p1, NccPatches::square(gray1, p1, params_.halfWindow), p2,
               NccPatches::square(gray2, p2, params_.halfWindow), params_.searchHalfWidthPx * s,
               params_.searchHalfHeightPx * s);
}

}  // namespace reftrack
