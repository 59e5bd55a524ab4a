#include "engine/homography/RobustHomographyEstimator.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <numeric>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/homography/HomographyDlt.hpp"
#include "engine/homography/ProgressiveSampling.hpp"

namespace reftrack {

namespace {

// Progressive sampling never draws from fewer than this many top-ranked matches.
constexpr int kMinProgressivePool = 8;

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
                             const std::vector<cv::Point2f>& dst, const std::vector<int>& indices,
                             const std::vector<double>& weights) {
  if (indices.size() < 5) return H;
  if (!weights.empty() && weights.size() != indices.size())
    throw Error("refine homography: one weight per index is required");
  const cv::Matx33d T1 = normalisingTransform(src, indices);
  const cv::Matx33d T2 = normalisingTransform(dst, indices);
  cv::Matx33d Hn = T2 * H * T1.inv();
  if (!(std::abs(Hn(2, 2)) > 1e-9)) return H;
  Hn *= 1.0 / Hn(2, 2);
  // Levenberg-Marquardt on the 8 free entries (h33 = 1) with the analytic Jacobian of the
  // transfer residual; an 8x8 normal-equation solve per step (the problem is tiny: a general
  // solver's setup cost would dominate).
  std::vector<Eigen::Vector4d> pts;  // normalised (x, y, u, v)
  std::vector<double> w(indices.size(), 1.0);
  pts.reserve(indices.size());
  for (size_t k = 0; k < indices.size(); ++k) {
    const auto& a = src[static_cast<size_t>(indices[k])];
    const auto& b = dst[static_cast<size_t>(indices[k])];
    pts.emplace_back(T1(0, 0) * a.x + T1(0, 2), T1(1, 1) * a.y + T1(1, 2),
                     T2(0, 0) * b.x + T2(0, 2), T2(1, 1) * b.y + T2(1, 2));
    if (!weights.empty()) w[k] = weights[k];
  }
  using Vec8 = Eigen::Matrix<double, 8, 1>;
  using Mat8 = Eigen::Matrix<double, 8, 8>;
  Vec8 h;
  h << Hn(0, 0), Hn(0, 1), Hn(0, 2), Hn(1, 0), Hn(1, 1), Hn(1, 2), Hn(2, 0), Hn(2, 1);
  // Sum of squared residuals; with JtJ (lower triangle) and Jtr when asked. With a = (x, y, 1) / w
  // the two Jacobian rows are (a, 0, -px a_xy) and (0, a, -py a_xy): JtJ has the blocks
  // S = sum wk a a^T (twice on the diagonal), -sum wk px a a_xy^T, -sum wk py a a_xy^T and
  // sum wk (px^2 + py^2) a_xy a_xy^T, so 21 products per point are summed instead of two dense
  // 8x8 rank updates (measured with callgrind on bench-homography 1280x720 frames: the rank
  // updates were 17% of a tracked frame's instructions, through HomographyRefiner).
  const auto evaluate = [&pts, &w](const Vec8& p, Mat8* JtJ, Vec8* Jtr) {
    double cost = 0;
    double s00 = 0, s01 = 0, s02 = 0, s11 = 0, s12 = 0, s22 = 0;  // S
    double x00 = 0, x01 = 0, x11 = 0, x20 = 0, x21 = 0;           // sum wk px a_i a_k
    double y00 = 0, y01 = 0, y11 = 0, y20 = 0, y21 = 0;           // sum wk py a_i a_k
    double q00 = 0, q01 = 0, q11 = 0;                             // sum wk (px^2+py^2) a_k a_l
    double g0 = 0, g1 = 0, g2 = 0, g3 = 0, g4 = 0, g5 = 0, g6 = 0, g7 = 0;  // Jtr
    for (size_t k = 0; k < pts.size(); ++k) {
      const Eigen::Vector4d& q = pts[k];
      const double wk = w[k];
      const double x = q(0), y = q(1);
      const double w = p(6) * x + p(7) * y + 1.0;
      if (!(std::abs(w) > 1e-12)) return std::numeric_limits<double>::infinity();
      const double iw = 1.0 / w;
      const double px = (p(0) * x + p(1) * y + p(2)) * iw;
      const double py = (p(3) * x + p(4) * y + p(5)) * iw;
      const double rx = px - q(2), ry = py - q(3);
      cost += wk * (rx * rx + ry * ry);
      if (!JtJ) continue;
      const double a0 = x * iw, a1 = y * iw, a2 = iw;
      const double w0 = wk * a0, w1 = wk * a1, w2 = wk * a2;
      const double s00k = w0 * a0, s01k = w0 * a1, s11k = w1 * a1;
      s00 += s00k;
      s01 += s01k;
      s02 += w0 * a2;
      s11 += s11k;
      s12 += w1 * a2;
      s22 += w2 * a2;
      const double s20k = w2 * a0, s21k = w2 * a1;
      x00 += px * s00k;
      x01 += px * s01k;
      x11 += px * s11k;
      x20 += px * s20k;
      x21 += px * s21k;
      y00 += py * s00k;
      y01 += py * s01k;
      y11 += py * s11k;
      y20 += py * s20k;
      y21 += py * s21k;
      const double rr = px * px + py * py;
      q00 += rr * s00k;
      q01 += rr * s01k;
      q11 += rr * s11k;
      g0 += w0 * rx;
      g1 += w1 * rx;
      g2 += w2 * rx;
      g3 += w0 * ry;
      g4 += w1 * ry;
      g5 += w2 * ry;
      const double e = px * rx + py * ry;
      g6 -= w0 * e;
      g7 -= w1 * e;
    }
    if (JtJ) {
      Mat8& A = *JtJ;
      A.setZero();
      // Lower triangle, row by row.
      A(0, 0) = s00;
      A(1, 0) = s01, A(1, 1) = s11;
      A(2, 0) = s02, A(2, 1) = s12, A(2, 2) = s22;
      A(3, 3) = s00;
      A(4, 3) = s01, A(4, 4) = s11;
      A(5, 3) = s02, A(5, 4) = s12, A(5, 5) = s22;
      A(6, 0) = -x00, A(6, 1) = -x01, A(6, 2) = -x20;
      A(7, 0) = -x01, A(7, 1) = -x11, A(7, 2) = -x21;
      A(6, 3) = -y00, A(6, 4) = -y01, A(6, 5) = -y20;
      A(7, 3) = -y01, A(7, 4) = -y11, A(7, 5) = -y21;
      A(6, 6) = q00;
      A(7, 6) = q01, A(7, 7) = q11;
      *Jtr << g0, g1, g2, g3, g4, g5, g6, g7;
    }
    return cost;
  };
  Mat8 JtJ;
  Vec8 Jtr;
  double cost = evaluate(h, &JtJ, &Jtr);
  if (!std::isfinite(cost)) return H;
  double lambda = 1e-4;
  for (int it = 0; it < 10; ++it) {
    Mat8 A = JtJ.selfadjointView<Eigen::Lower>();
    A.diagonal() *= 1.0 + lambda;
    const Vec8 step = A.ldlt().solve(-Jtr);
    if (!step.allFinite()) break;
    const Vec8 trial = h + step;
    Mat8 trialJtJ;
    Vec8 trialJtr;
    const double trialCost = evaluate(trial, &trialJtJ, &trialJtr);
    if (std::isfinite(trialCost) && trialCost < cost) {
      const bool converged = cost - trialCost < 1e-10 * cost;
      h = trial;
      cost = trialCost;
      JtJ = trialJtJ;
      Jtr = trialJtr;
      lambda = std::max(1e-9, lambda * 0.1);
      if (converged) break;
    } else {
      lambda *= 10.0;
      if (lambda > 1e6) break;
    }
  }
  const cv::Matx33d Hr(h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), 1.0);
  cv::Matx33d out = T2.inv() * Hr * T1;
  if (!(std::abs(out(2, 2)) > 1e-12)) return H;
  out *= 1.0 / out(2, 2);
  for (int k = 0; k < 9; ++k)
    if (!std::isfinite(out.val[k])) return H;
  return out;
}

void summariseEstimate(HomographyEstimate& out, const cv::Matx33d& H,
                       const std::vector<int>& inliers, const std::vector<cv::Point2f>& src,
                       const std::vector<cv::Point2f>& dst, const RansacParams& params) {
  out.H = H;
  out.inliers.assign(src.size(), 0);
  double sq = 0;
  for (int i : inliers) {
    out.inliers[static_cast<size_t>(i)] = 1;
    const double e = transferError(H, src[static_cast<size_t>(i)], dst[static_cast<size_t>(i)]);
    sq += e * e;
  }
  out.inlierCount = static_cast<int>(inliers.size());
  out.inlierRatio = src.empty() ? 0.0 : static_cast<double>(out.inlierCount) / src.size();
  out.rmsTransferError = out.inlierCount > 0 ? std::sqrt(sq / out.inlierCount) : 0.0;
  out.success = false;
  if (out.inlierRatio < params.minInlierRatio)
    out.failure = "inlier ratio " + std::to_string(out.inlierRatio) + " below minimum";
  else if (out.inlierCount < params.minInliers)
    out.failure = "only " + std::to_string(out.inlierCount) + " inliers";
  else
    out.success = true;
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
                                                       cv::Size imageSize,
                                                       const std::vector<float>& quality,
                                                       cv::Size dstSize) const {
  requireMatchLists("robust homography", src, dst, quality);
  HomographyEstimate out;
  const int n = static_cast<int>(src.size());
  out.inliers.assign(static_cast<size_t>(n), 0);
  if (n < std::max(4, params_.minInliers)) {
    out.failure = "too few matches (" + std::to_string(n) + ")";
    return out;
  }
  const double spacing = params_.minSampleSpacingPx * resolutionScale(imageSize);
  const double threshold =
      params_.inlierThresholdPx * resolutionScale(dstSize.area() > 0 ? dstSize : imageSize);
  cv::RNG rng(static_cast<uint64_t>(params_.seed) + 0x9E3779B97F4A7C15ull);

  // Sampling order: best quality first when progressive (PROSAC).
  const ProgressiveSampling sampling(quality, n, params_.progressiveSampling, params_.maxIterations,
                                     4, kMinProgressivePool);

  // One RANSAC pass with samples pairwise >= minSpacing apart; returns the best support.
  const auto ransacPass = [&](double minSpacing) {
    const double spacing2 = minSpacing * minSpacing;
    std::vector<int> bestInliers;
    int sample[4] = {0, 0, 0, 0};
    for (int it = 0; it < params_.maxIterations; ++it) {
      ++out.iterations;
      // Draw 4 points of the pool pairwise >= spacing apart (a bounded number of tries per
      // iteration; a pool that cannot provide them is widened).
      bool drawn = false;
      for (int pool = sampling.pool(it); !drawn; pool = std::min(n, 2 * pool)) {
        for (int attempt = 0; attempt < 40 && !drawn; ++attempt) {
          int k = 0;
          for (int tries = 0; k < 4 && tries < 40; ++tries) {
            const int c = sampling.matchAt(rng.uniform(0, pool));
            bool ok = true;
            for (int m = 0; m < k && ok; ++m) {
              const cv::Point2f d =
                  src[static_cast<size_t>(c)] - src[static_cast<size_t>(sample[m])];
              ok = c != sample[m] && d.dot(d) >= spacing2;
            }
            if (ok) sample[k++] = c;
          }
          drawn = k == 4;
        }
        if (pool == n) break;
      }
      if (!drawn) continue;
      const auto H = homographyFromFourPoints(src, dst, sample);
      if (!H || !acceptable(*H)) continue;
      std::vector<int> in = inliersOf(*H, src, dst, threshold);
      if (in.size() > bestInliers.size()) bestInliers = std::move(in);
      if (it + 1 >= params_.earlyAcceptMinIterations &&
          static_cast<double>(bestInliers.size()) > params_.earlyAcceptSupport * n)
        break;
    }
    return bestInliers;
  };
  std::vector<int> bestInliers = ransacPass(spacing);
  // When the true matches cover only a strip of the image (a frame that barely overlaps the
  // reference), few 4-point samples spread that far consist of inliers only: a pass that would
  // fail is repeated once with half the spacing (measured on the 33 degree rotation sweep at
  // 320x240, 24 degrees, overlap 0.28: 12 of 20 registered with 60 px, 20 of 20 with 30 px).
  const auto failing = [&](const std::vector<int>& in) {
    return static_cast<int>(in.size()) < std::max(4, params_.minInliers) ||
           static_cast<double>(in.size()) < params_.minInlierRatio * n;
  };
  if (failing(bestInliers)) {
    std::vector<int> closer = ransacPass(0.5 * spacing);
    if (closer.size() > bestInliers.size()) bestInliers = std::move(closer);
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
  summariseEstimate(out, H, bestInliers, src, dst, params_);
  if (!acceptable(H)) {
    out.success = false;
    out.failure = "near-singular homography";
  }
  return out;
}

}  // namespace reftrack
