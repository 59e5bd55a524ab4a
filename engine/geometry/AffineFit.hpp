#pragma once
// The least-squares affine map through point pairs (source -> destination), as the wide-baseline
// matcher's local maps L (paper Eq. 18) and the pose check's local warps use it: centred on the
// sources' mean for conditioning, 3x3 normal equations (fixed size: it runs per corner and frame).
#include <Eigen/Dense>
#include <cmath>
#include <opencv2/core.hpp>
#include <utility>
#include <vector>

namespace reftrack {

enum class AffineFit {
  Fitted,
  TooFew,      // fewer than 3 pairs
  Collinear,   // the sources' spread across their line is under ~1 px (more pairs may help)
  Degenerate,  // |det| of the linear part outside [1e-3, 1e3] or not finite
};

// pair(j) for j in [0, count) gives {source, destination} (cv::Point2d-convertible); on Fitted,
// A holds the map (last row 0 0 1).
template <class PairAt>
AffineFit fitAffine(int count, const PairAt& pair, cv::Matx33d& A) {
  if (count < 3) return AffineFit::TooFew;
  cv::Point2d mean(0, 0);
  for (int j = 0; j < count; ++j) mean += cv::Point2d(pair(j).first);
  mean *= 1.0 / count;
  Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, 2> Atb = Eigen::Matrix<double, 3, 2>::Zero();
  for (int j = 0; j < count; ++j) {
    const auto [source, destination] = pair(j);
    const Eigen::Vector3d a(source.x - mean.x, source.y - mean.y, 1.0);
    AtA += a * a.transpose();
    Atb.col(0) += a * static_cast<double>(destination.x);
    Atb.col(1) += a * static_cast<double>(destination.y);
  }
  // The smaller eigenvalue of the symmetric 2x2 block, in closed form.
  const double sxx = AtA(0, 0), syy = AtA(1, 1), sxy = AtA(0, 1);
  if (0.5 * (sxx + syy) - std::sqrt(0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy) < 1.0)
    return AffineFit::Collinear;
  const Eigen::Matrix<double, 3, 2> X = AtA.ldlt().solve(Atb);  // [a11 a21; a12 a22; tx ty]
  const double a11 = X(0, 0), a12 = X(1, 0), a21 = X(0, 1), a22 = X(1, 1);
  const double det = a11 * a22 - a12 * a21;
  if (!std::isfinite(det) || std::abs(det) < 1e-3 || std::abs(det) > 1e3)
    return AffineFit::Degenerate;
  A = cv::Matx33d(a11, a12, X(2, 0) - a11 * mean.x - a12 * mean.y, a21, a22,
                  X(2, 1) - a21 * mean.x - a22 * mean.y, 0, 0, 1);
  return AffineFit::Fitted;
}

// The local affine map (reference pixels -> frame) at point i, as the pose check and the keypoint
// measurements warp a reference window: through i's reference pixel and projection and those of
// its neighbours whose projection is finite. referencePixel(k) gives point k's reference pixel;
// `pairs` is scratch storage, reused across calls.
template <class PixelAt>
AffineFit fitLocalAffine(std::size_t i, const std::vector<int>& neighbours,
                         const PixelAt& referencePixel, const std::vector<cv::Point2d>& projected,
                         std::vector<std::pair<cv::Point2d, cv::Point2d>>& pairs, cv::Matx33d& A) {
  pairs.assign(1, {cv::Point2d(referencePixel(i)), projected[i]});
  for (int j : neighbours) {
    const auto k = static_cast<std::size_t>(j);
    if (std::isfinite(projected[k].x))
      pairs.emplace_back(cv::Point2d(referencePixel(k)), projected[k]);
  }
  return fitAffine(
      static_cast<int>(pairs.size()), [&](int j) { return pairs[static_cast<std::size_t>(j)]; }, A);
}

}  // namespace reftrack
