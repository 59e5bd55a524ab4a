#include "engine/homography/RotationHomographyEstimator.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/homography/HomographyDlt.hpp"
#include "engine/homography/ProgressiveSampling.hpp"

namespace reftrack {

namespace {

// Progressive sampling never draws from fewer than this many top-ranked matches.
constexpr int kMinProgressivePool = 6;

Eigen::Vector3d bearing(const Eigen::Matrix3d& Kinv, const cv::Point2f& p) {
  return (Kinv * Eigen::Vector3d(p.x, p.y, 1.0)).normalized();
}

}  // namespace

Eigen::Matrix3d bestRotation(const std::vector<Eigen::Vector3d>& a,
                             const std::vector<Eigen::Vector3d>& b,
                             const std::vector<int>& indices) {
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  for (int i : indices) M += b[static_cast<size_t>(i)] * a[static_cast<size_t>(i)].transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

RotationHomographyEstimator::RotationHomographyEstimator(const Eigen::Matrix3d& K,
                                                         RansacParams params)
    : K_(K), params_(params) {
  params_.check();
  const double det = K.determinant();
  if (!K.allFinite() || !(std::abs(det) > 1e-12))
    throw Error("rotation homography: the camera matrix K is not invertible");
  Kinv_ = K.inverse();
}

HomographyEstimate RotationHomographyEstimator::estimate(const std::vector<cv::Point2f>& src,
                                                         const std::vector<cv::Point2f>& dst,
                                                         cv::Size imageSize,
                                                         const std::vector<float>& quality) const {
  requireMatchLists("rotation homography", src, dst, quality);
  HomographyEstimate out;
  const int n = static_cast<int>(src.size());
  out.inliers.assign(static_cast<size_t>(n), 0);
  if (n < std::max(2, params_.minInliers)) {
    out.failure = "too few matches (" + std::to_string(n) + ")";
    return out;
  }
  std::vector<Eigen::Vector3d> a(static_cast<size_t>(n)), b(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    a[static_cast<size_t>(i)] = bearing(Kinv_, src[static_cast<size_t>(i)]);
    b[static_cast<size_t>(i)] = bearing(Kinv_, dst[static_cast<size_t>(i)]);
  }
  const double threshold = params_.inlierThresholdPx * resolutionScale(imageSize);
  // The two sampled matches a quarter of the 4-point spacing apart: two points fix a rotation,
  // but too close together they leave the roll about them loosely determined.
  const double spacing = 0.25 * params_.minSampleSpacingPx * resolutionScale(imageSize);
  // A rotation keeps the angle between two bearings: a sample whose angles differ by more than
  // the inlier threshold allows (in radians, at the focal length) cannot be two inliers.
  const double angleTolerance = 2.0 * threshold / K_(0, 0);
  const auto toH = [&](const Eigen::Matrix3d& R) {
    const Eigen::Matrix3d He = K_ * R * Kinv_;
    cv::Matx33d H;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) H(r, c) = He(r, c) / He(2, 2);
    return H;
  };
  const auto inliersOf = [&](const Eigen::Matrix3d& R) {
    std::vector<int> in;
    const Eigen::Matrix3d P = K_ * R;
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d q = P * a[static_cast<size_t>(i)];
      if (!(q.z() > 1e-12)) continue;
      const double dx = q.x() / q.z() - dst[static_cast<size_t>(i)].x;
      const double dy = q.y() / q.z() - dst[static_cast<size_t>(i)].y;
      if (dx * dx + dy * dy < threshold * threshold) in.push_back(i);
    }
    return in;
  };

  // Best quality first when progressive (PROSAC, pairs).
  const ProgressiveSampling sampling(quality, n, params_.progressiveSampling, params_.maxIterations,
                                     2, kMinProgressivePool);
  cv::RNG rng(static_cast<uint64_t>(params_.seed) + 0x7F4A7C159E3779B9ull);
  std::vector<int> best;
  for (int it = 0; it < params_.maxIterations; ++it) {
    ++out.iterations;
    const int pool = sampling.pool(it);
    int i = -1, j = -1;
    for (int tries = 0; tries < 40 && j < 0; ++tries) {
      const int x = sampling.matchAt(rng.uniform(0, pool));
      const int y = sampling.matchAt(rng.uniform(0, pool));
      const cv::Point2f d = src[static_cast<size_t>(x)] - src[static_cast<size_t>(y)];
      if (x != y && d.dot(d) >= spacing * spacing) i = x, j = y;
    }
    if (j < 0) continue;
    const double angleA =
        std::acos(std::clamp(a[static_cast<size_t>(i)].dot(a[static_cast<size_t>(j)]), -1.0, 1.0));
    const double angleB =
        std::acos(std::clamp(b[static_cast<size_t>(i)].dot(b[static_cast<size_t>(j)]), -1.0, 1.0));
    if (std::abs(angleA - angleB) > angleTolerance) continue;
    std::vector<int> in = inliersOf(bestRotation(a, b, {i, j}));
    if (in.size() > best.size()) best = std::move(in);
    if (it + 1 >= params_.earlyAcceptMinIterations &&
        static_cast<double>(best.size()) > params_.earlyAcceptSupport * n)
      break;
  }
  if (best.size() < 2) {
    out.failure = "no consistent pair of matches for a rotation";
    return out;
  }
  // The rotation of all inliers, until the inlier set is stable.
  Eigen::Matrix3d R = bestRotation(a, b, best);
  for (int round = 0; round < 5; ++round) {
    std::vector<int> in = inliersOf(R);
    if (in == best || in.size() < 2) break;
    best = std::move(in);
    R = bestRotation(a, b, best);
  }
  summariseEstimate(out, toH(R), best, src, dst, params_);
  return out;
}

}  // namespace reftrack
