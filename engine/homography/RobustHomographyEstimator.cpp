#include "engine/homography/RobustHomographyEstimator.hpp"

#include <ceres/ceres.h>

#include <cmath>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/homography/HomographyDlt.hpp"

namespace reftrack {

namespace {

struct TransferResidual {
  double x, y, u, v, scale;  // normalised src (x, y), dst (u, v); scale: back to pixels
  template <class T>
  bool operator()(const T* h, T* r) const {
    const T w = h[6] * x + h[7] * y + T(1.0);
    r[0] = ((h[0] * x + h[1] * y + h[2]) / w - u) * scale;
    r[1] = ((h[3] * x + h[4] * y + h[5]) / w - v) * scale;
    return true;
  }
};

std::vector<int> inliersOf(const cv::Matx33d& H, const std::vector<cv::Point2f>& src,
                           const std::vector<cv::Point2f>& dst, double threshold) {
  std::vector<int> in;
  const double t2 = threshold * threshold;
  for (size_t i = 0; i < src.size(); ++i) {
    const cv::Point2d q = transferPoint(H, cv::Point2d(src[i].x, src[i].y));
    const double dx = q.x - dst[i].x, dy = q.y - dst[i].y;
    if (dx * dx + dy * dy < t2) in.push_back(static_cast<int>(i));
  }
  return in;
}

}  // namespace

cv::Matx33d refineHomography(const cv::Matx33d& H, const std::vector<cv::Point2f>& src,
                             const std::vector<cv::Point2f>& dst, const std::vector<int>& indices) {
  if (indices.size() < 5) return H;
  const cv::Matx33d T1 = normalisingTransform(src, indices);
  const cv::Matx33d T2 = normalisingTransform(dst, indices);
  cv::Matx33d Hn = T2 * H * T1.inv();
  if (!(std::abs(Hn(2, 2)) > 1e-9)) return H;
  Hn *= 1.0 / Hn(2, 2);
  double h[8] = {Hn(0, 0), Hn(0, 1), Hn(0, 2), Hn(1, 0), Hn(1, 1), Hn(1, 2), Hn(2, 0), Hn(2, 1)};
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  const double toPixels = 1.0 / T2(0, 0);
  for (int i : indices) {
    const auto& a = src[static_cast<size_t>(i)];
    const auto& b = dst[static_cast<size_t>(i)];
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<TransferResidual, 2, 8>(
            new TransferResidual{T1(0, 0) * a.x + T1(0, 2), T1(1, 1) * a.y + T1(1, 2),
                                 T2(0, 0) * b.x + T2(0, 2), T2(1, 1) * b.y + T2(1, 2), toPixels}),
        nullptr, h);
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 10;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (!summary.IsSolutionUsable()) return H;
  const cv::Matx33d Hr(h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], 1.0);
  cv::Matx33d out = T2.inv() * Hr * T1;
  if (!(std::abs(out(2, 2)) > 1e-12)) return H;
  out *= 1.0 / out(2, 2);
  for (int k = 0; k < 9; ++k)
    if (!std::isfinite(out.val[k])) return H;
  return out;
}

RobustHomographyEstimator::RobustHomographyEstimator(RansacParams params) : params_(params) {
  params_.check();
}

bool RobustHomographyEstimator::acceptable(const cv::Matx33d& H) const {
  for (int k = 0; k < 9; ++k)
    if (!std::isfinite(H.val[k])) return false;
  if (!(std::abs(H(2, 2)) > 1e-12)) return false;
  const double det = std::abs(cv::determinant(H * (1.0 / H(2, 2))));
  return det >= params_.minDeterminant && det <= 1.0 / params_.minDeterminant;
}

HomographyEstimate RobustHomographyEstimator::estimate(const std::vector<cv::Point2f>& src,
                                                       const std::vector<cv::Point2f>& dst,
                                                       cv::Size imageSize) const {
  if (src.size() != dst.size())
    throw Error("robust homography: " + std::to_string(src.size()) + " source points but " +
                std::to_string(dst.size()) + " destination points");
  HomographyEstimate out;
  const int n = static_cast<int>(src.size());
  out.inliers.assign(static_cast<size_t>(n), 0);
  if (n < std::max(4, params_.minInliers)) {
    out.failure = "too few matches (" + std::to_string(n) + ")";
    return out;
  }
  const double spacing = params_.minSampleSpacingPx * resolutionScale(imageSize);
  const double threshold = params_.inlierThresholdPx * resolutionScale(imageSize);
  const double spacing2 = spacing * spacing;
  cv::RNG rng(static_cast<uint64_t>(params_.seed) + 0x9E3779B97F4A7C15ull);
  std::vector<int> bestInliers;
  std::vector<int> sample(4);
  for (int it = 0; it < params_.maxIterations; ++it) {
    out.iterations = it + 1;
    // Draw 4 points pairwise >= spacing apart (a bounded number of tries per iteration).
    bool drawn = false;
    for (int attempt = 0; attempt < 40 && !drawn; ++attempt) {
      int k = 0;
      for (int tries = 0; k < 4 && tries < 40; ++tries) {
        const int c = rng.uniform(0, n);
        bool ok = true;
        for (int m = 0; m < k && ok; ++m) {
          const cv::Point2f d = src[static_cast<size_t>(c)] - src[static_cast<size_t>(sample[m])];
          ok = c != sample[m] && d.dot(d) >= spacing2;
        }
        if (ok) sample[static_cast<size_t>(k++)] = c;
      }
      drawn = k == 4;
    }
    if (!drawn) continue;
    const auto H = homographyDlt(src, dst, sample);
    if (!H || !acceptable(*H)) continue;
    std::vector<int> in = inliersOf(*H, src, dst, threshold);
    if (in.size() > bestInliers.size()) bestInliers = std::move(in);
    if (it + 1 >= params_.earlyAcceptMinIterations &&
        static_cast<double>(bestInliers.size()) > params_.earlyAcceptSupport * n)
      break;
  }
  if (bestInliers.size() < 4) {
    out.failure = "no acceptable 4-point sample (points too close together or degenerate)";
    return out;
  }
  // Re-estimate from all inliers until the set is stable, then refine the transfer error.
  cv::Matx33d H;
  bool haveH = false;
  for (int round = 0; round < 3; ++round) {
    const auto Hi = homographyDlt(src, dst, bestInliers);
    if (!Hi || !acceptable(*Hi)) break;
    H = *Hi;
    haveH = true;
    std::vector<int> in = inliersOf(H, src, dst, threshold);
    if (in == bestInliers || in.size() < 4) break;
    bestInliers = std::move(in);
  }
  if (!haveH) {
    out.failure = "the homography of the inliers is degenerate or near-singular";
    return out;
  }
  if (params_.refine) {
    H = refineHomography(H, src, dst, bestInliers);
    std::vector<int> in = inliersOf(H, src, dst, threshold);
    if (in.size() >= 4) bestInliers = std::move(in);
  }
  out.H = H;
  double sq = 0;
  for (int i : bestInliers) {
    out.inliers[static_cast<size_t>(i)] = 1;
    const double e = transferError(H, src[static_cast<size_t>(i)], dst[static_cast<size_t>(i)]);
    sq += e * e;
  }
  out.inlierCount = static_cast<int>(bestInliers.size());
  out.inlierRatio = static_cast<double>(out.inlierCount) / n;
  out.rmsTransferError = out.inlierCount > 0 ? std::sqrt(sq / out.inlierCount) : 0.0;
  if (!acceptable(H))
    out.failure = "near-singular homography";
  else if (out.inlierRatio < params_.minInlierRatio)
    out.failure = "inlier ratio " + std::to_string(out.inlierRatio) + " below minimum";
  else if (out.inlierCount < params_.minInliers)
    out.failure = "only " + std::to_string(out.inlierCount) + " inliers";
  else
    out.success = true;
  return out;
}

}  // namespace reftrack
