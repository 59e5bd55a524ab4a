#pragma once
// Progressive sampling (PROSAC, Chum & Matas 2005) for the robust estimators: the matches ranked
// by quality, best first, and iteration t of T drawing its minimal sample from the top n_t — the
// smallest pool with T C(n_t, m) / C(N, m) >= t + 1, never below a minimum — so the best-ranked
// matches are tried first and every match is in the pool by the last iteration. Without quality
// values (or switched off) the order is the input order and the pool is all N.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace reftrack {

class ProgressiveSampling {
 public:
  // quality: one value per match (higher = more likely correct) or empty; sampleSize m >= 1.
  ProgressiveSampling(const std::vector<float>& quality, int matches, bool progressive,
                      int maxIterations, int sampleSize, int minPool);

  int pool(int iteration) const;  // n_t: draw from ranks [0, n_t)
  int matchAt(int rank) const { return order_[static_cast<size_t>(rank)]; }

 private:
  std::vector<int> order_;
  bool progressive_;
  int maxIterations_, sampleSize_, minPool_;
};

// Throws reftrack::Error starting with `who` unless src and dst have the same length and quality
// is empty or one value per match.
void requireMatchLists(const std::string& who, const std::vector<cv::Point2f>& src,
                       const std::vector<cv::Point2f>& dst, const std::vector<float>& quality);

}  // namespace reftrack
