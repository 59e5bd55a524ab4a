#include "engine/tracking/WideBaselineMatcher.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/tracking/WarpedCorrelation.hpp"

namespace reftrack {

MatchableReference MatchableReference::build(const cv::Mat& image,
                                             std::vector<cv::Point2f> corners) {
  if (image.empty()) throw Error("MatchableReference: empty reference image");
  MatchableReference r;
  cv::Mat gray = image;
  if (image.channels() == 3) cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  gray.convertTo(r.imageF, CV_32F);
  r.corners = std::move(corners);
  r.grid = CornerGrid(r.corners, image.size(), 32);
  return r;
}

namespace {
inline cv::Point2d apply(const cv::Matx33d& M, cv::Point2d p) {
  const cv::Vec3d q = M * cv::Vec3d(p.x, p.y, 1.0);
  return {q[0] / q[2], q[1] / q[2]};
}
}  // namespace

bool WideBaselineMatcher::localAffine(cv::Point2d p, const std::vector<PreviousMatch>& previous,
                                      const MatchableReference& reference, cv::Matx33d& L) const {
  std::vector<int> all(previous.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  return localAffineFrom(p, previous, all, reference, L);
}

bool WideBaselineMatcher::localAffineFrom(cv::Point2d p, const std::vector<PreviousMatch>& previous,
                                          const std::vector<int>& nearby,
                                          const MatchableReference& reference,
                                          cv::Matx33d& L) const {
  const int k = params_.affineNeighbours;
  if (static_cast<int>(nearby.size()) < 3) return false;
  // The nearest previous matches (partial selection over the nearby ones).
  thread_local std::vector<std::pair<double, int>> byDistance;
  byDistance.clear();
  for (int i : nearby) {
    const cv::Point2d d = cv::Point2d(previous[static_cast<std::size_t>(i)].previous) - p;
    byDistance.emplace_back(d.dot(d), i);
  }
  const int available = static_cast<int>(byDistance.size());
  const int most = std::min(std::max(k, 8), available);
  std::partial_sort(byDistance.begin(), byDistance.begin() + most, byDistance.end());
  // Take more than k when the nearest are nearly collinear: grow until well conditioned.
  for (int count = std::min(k, available); count <= most; ++count) {
    // Least-squares affine from the `count` pairs, centred on their mean for conditioning:
    // 3x3 normal equations (fixed size; this runs for every corner of every frame).
    cv::Point2d mean(0, 0);
    for (int j = 0; j < count; ++j)
      mean += cv::Point2d(
          previous[static_cast<std::size_t>(byDistance[static_cast<std::size_t>(j)].second)]
              .previous);
    mean *= 1.0 / count;
    Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
    Eigen::Matrix<double, 3, 2> Atb = Eigen::Matrix<double, 3, 2>::Zero();
    for (int j = 0; j < count; ++j) {
      const PreviousMatch& m =
          previous[static_cast<std::size_t>(byDistance[static_cast<std::size_t>(j)].second)];
      const cv::Point2f& r = reference.corners[static_cast<std::size_t>(m.referenceCorner)];
      const Eigen::Vector3d a(m.previous.x - mean.x, m.previous.y - mean.y, 1.0);
      AtA += a * a.transpose();
      Atb.col(0) += a * r.x;
      Atb.col(1) += a * r.y;
    }
    // Collinear (or coincident) neighbours: the spread across their line is below ~1 px.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> spread(AtA.topLeftCorner<2, 2>());
    if (spread.eigenvalues()(0) < 1.0) continue;
    const Eigen::Matrix<double, 3, 2> X = AtA.ldlt().solve(Atb);  // [a11 a21; a12 a22; tx ty]
    const double a11 = X(0, 0), a12 = X(1, 0), a21 = X(0, 1), a22 = X(1, 1);
    const double tx = X(2, 0) - a11 * mean.x - a12 * mean.y;
    const double ty = X(2, 1) - a21 * mean.x - a22 * mean.y;
    const double det = a11 * a22 - a12 * a21;
    if (!std::isfinite(det) || std::abs(det) < 1e-3 || std::abs(det) > 1e3) return false;
    L = cv::Matx33d(a11, a12, tx, a21, a22, ty, 0, 0, 1);
    return true;
  }
  return false;
}

std::vector<WideBaselineMatch> WideBaselineMatcher::match(
    const cv::Mat& frameF, const std::vector<cv::Point2f>& frameCorners,
    const cv::Matx33d& H_kToPrev, const std::vector<PreviousMatch>& previous,
    const MatchableReference& reference) const {
  std::vector<WideBaselineMatch> matches;
  if (previous.size() < 3 || frameCorners.empty() || reference.corners.empty()) return matches;
  const WarpedCorrelation correlation(frameF, reference.imageF, params_.halfWindow);
  const double scale = resolutionScale(frameF.size());
  const double hx = params_.dx * scale, hy = params_.dy * scale;

  std::vector<int> candidates, nearby;
  // The best frame corner per reference corner.
  std::vector<WideBaselineMatch> best(reference.corners.size());
  // Previous matches on a grid: the local affine needs only those near each predicted position.
  std::vector<cv::Point2f> previousPositions;
  for (const PreviousMatch& m : previous) previousPositions.push_back(m.previous);
  const CornerGrid previousGrid(previousPositions, frameF.size(), 40);
  for (int i = 0; i < static_cast<int>(frameCorners.size()); ++i) {
    const cv::Point2d pK(frameCorners[static_cast<std::size_t>(i)]);
    const cv::Point2d pPrev = apply(H_kToPrev, pK);
    cv::Matx33d L;
    // Nearby previous matches: widen the window until at least 8 are found (or all are).
    for (double half = 40.0;; half *= 2.0) {
      previousGrid.query(pPrev, half, half, nearby);
      if (nearby.size() >= 8 || nearby.size() == previous.size() || half > 4.0 * frameF.cols) break;
    }
    if (!localAffineFrom(pPrev, previous, nearby, reference, L)) continue;
    const cv::Matx33d W = L * H_kToPrev;
    const cv::Point2d pA = apply(W, pK);
    reference.grid.query(pA, hx, hy, candidates);
    if (candidates.empty()) continue;
    const WarpedCorrelation::FramePatch patch =
        correlation.framePatch(frameCorners[static_cast<std::size_t>(i)]);
    if (!patch.valid()) continue;
    double bestScore = params_.minScore;
    int bestRef = -1;
    for (int c : candidates) {
      const double s =
          correlation.score(patch, W, cv::Point2d(reference.corners[static_cast<std::size_t>(c)]));
      if (s > bestScore) {
        bestScore = s;
        bestRef = c;
      }
    }
    if (bestRef < 0) continue;
    WideBaselineMatch& slot = best[static_cast<std::size_t>(bestRef)];
    if (slot.frameCorner < 0 || bestScore > slot.score) slot = {i, bestRef, bestScore, pA};
  }
  for (const WideBaselineMatch& m : best)
    if (m.frameCorner >= 0) matches.push_back(m);
  return matches;
}

}  // namespace reftrack
