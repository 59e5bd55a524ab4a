#include "engine/homography/ProgressiveSampling.hpp"

#include <algorithm>
#include <numeric>

#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

// C(n, m) as a real number (0 when n < m).
double choose(double n, int m) {
  double c = 1.0;
  for (int k = 0; k < m; ++k) c *= (n - k) / (k + 1);
  return std::max(0.0, c);
}

}  // namespace

ProgressiveSampling::ProgressiveSampling(const std::vector<float>& quality, int matches,
                                         bool progressive, int maxIterations, int sampleSize,
                                         int minPool)
    : order_(static_cast<size_t>(std::max(0, matches))),
      progressive_(progressive && !quality.empty()),
      maxIterations_(maxIterations),
      sampleSize_(std::max(1, sampleSize)),
      minPool_(minPool) {
  std::iota(order_.begin(), order_.end(), 0);
  if (progressive_)
    std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) {
      return quality[static_cast<size_t>(a)] > quality[static_cast<size_t>(b)];
    });
}

int ProgressiveSampling::pool(int iteration) const {
  const int n = static_cast<int>(order_.size());
  if (!progressive_) return n;
  const double perSample = maxIterations_ / choose(n, sampleSize_);
  int pool = std::min(n, minPool_);
  while (pool < n && perSample * choose(pool, sampleSize_) < iteration + 1) ++pool;
  return pool;
}

void requireMatchLists(const std::string& who, const std::vector<cv::Point2f>& src,
                       const std::vector<cv::Point2f>& dst, const std::vector<float>& quality) {
  if (src.size() != dst.size())
    throw Error(who + ": " + std::to_string(src.size()) + " source points but " +
                std::to_string(dst.size()) + " destination points");
  if (!quality.empty() && quality.size() != src.size())
    throw Error(who + ": " + std::to_string(quality.size()) + " quality values for " +
                std::to_string(src.size()) + " matches");
}

}  // namespace reftrack
