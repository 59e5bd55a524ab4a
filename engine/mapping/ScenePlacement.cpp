// Dominant-plane placement: 3-point RANSAC over the points near the median, least-squares refit
// (Eigen's symmetric eigensolver) on its inliers, then the base, axes and a rounded edge.
#include "engine/mapping/ScenePlacement.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "engine/core/Error.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack {

namespace {

constexpr int kMinPoints = 12;
constexpr int kRansacIterations = 500;  // a plane of >= 25% inliers: 1 - (1 - 0.25^3)^500 > 0.9996
// Inlier band: 2% of the considered points' median distance from their median (a 4 mm band for
// the desk clip's ~0.2 m spread; its triangulated points scatter ~1 mm off the desk).
constexpr double kThresholdFraction = 0.02;
constexpr double kMinInlierShare = 0.25;

double median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<long>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

Eigen::Vector3d coordinateMedian(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d m;
  for (int a = 0; a < 3; ++a) {
    std::vector<double> c;
    for (const Eigen::Vector3d& p : points) c.push_back(p[a]);
    m[a] = median(c);
  }
  return m;
}

struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit
  double offset = 0.0;                                // normal . x = offset on the plane
  double distance(const Eigen::Vector3d& x) const { return std::abs(normal.dot(x) - offset); }
};

// Least-squares plane through `points` (the smallest principal axis of their scatter).
Plane fitPlane(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) scatter += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  Plane plane;
  plane.normal = eig.eigenvectors().col(0).normalized();  // eigenvalues ascending
  plane.offset = plane.normal.dot(mean);
  return plane;
}

std::vector<Eigen::Vector3d> inliersOf(const Plane& plane, const std::vector<Eigen::Vector3d>& pts,
                                       double threshold) {
  std::vector<Eigen::Vector3d> in;
  for (const Eigen::Vector3d& p : pts)
    if (plane.distance(p) <= threshold) in.push_back(p);
  return in;
}

// The nearest of 1, 2 and 5 x 10^k to `x` in ratio.
double roundToOneTwoFive(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  double best = decade, bestRatio = 1e300;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    const double ratio = std::max(x / (m * decade), m * decade / x);
    if (ratio < bestRatio) {
      bestRatio = ratio;
      best = m * decade;
    }
  }
  return best;
}

}  // namespace

ScenePlacement placeOnDominantPlane(const std::vector<Eigen::Vector3d>& points,
                                    const std::vector<Eigen::Vector3d>& cameraCentres) {
  std::vector<Eigen::Vector3d> finite;
  for (const Eigen::Vector3d& p : points)
    if (p.allFinite()) finite.push_back(p);
  if (static_cast<int>(finite.size()) < kMinPoints)
    throw Error("scene placement: " + std::to_string(finite.size()) +
                " finite map points, at least " + std::to_string(kMinPoints) +
                " are needed to find the scene's plane");

  // The points nearest the median: the half of the scene around its middle.
  const Eigen::Vector3d centre = coordinateMedian(finite);
  std::sort(finite.begin(), finite.end(), [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return (a - centre).squaredNorm() < (b - centre).squaredNorm();
  });
  const std::size_t keep = std::max<std::size_t>(kMinPoints, finite.size() / 2);
  const std::vector<Eigen::Vector3d> near(finite.begin(), finite.begin() + static_cast<long>(keep));
  std::vector<double> radii;
  for (const Eigen::Vector3d& p : near) radii.push_back((p - centre).norm());
  const double spread = median(radii);
  if (!(spread > 0)) throw Error("scene placement: the map points coincide");
  const double threshold = kThresholdFraction * spread;

  // RANSAC on 3-point planes, deterministic (fixed seed).
  std::mt19937 rng(20261203u);
  std::uniform_int_distribution<std::size_t> pick(0, near.size() - 1);
  Plane best;
  std::size_t bestCount = 0;
  for (int it = 0; it < kRansacIterations; ++it) {
    const Eigen::Vector3d& a = near[pick(rng)];
    const Eigen::Vector3d& b = near[pick(rng)];
    const Eigen::Vector3d& c = near[pick(rng)];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() < 1e-12 * spread * spread) continue;  // collinear or repeated
    Plane plane;
    plane.normal = n.normalized();
    plane.offset = plane.normal.dot(a);
    std::size_t count = 0;
    for (const Eigen::Vector3d& p : near) count += plane.distance(p) <= threshold ? 1 : 0;
    if (count > bestCount) {
      bestCount = count;
      best = plane;
    }
  }
  if (bestCount < kMinInlierShare * static_cast<double>(near.size()))
    throw Error("scene placement: no plane holds a quarter of the " + std::to_string(near.size()) +
                " map points near the scene's middle (best " + std::to_string(bestCount) + ")");
  // Least squares on the inliers, twice (the refit may gain or lose points at the band's edge).
  std::vector<Eigen::Vector3d> inliers = inliersOf(best, near, threshold);
  for (int round = 0; round < 2; ++round) {
    const Plane refit = fitPlane(inliers);
    std::vector<Eigen::Vector3d> next = inliersOf(refit, near, threshold);
    if (next.size() < 3) break;
    best = refit;
    inliers = std::move(next);
  }

  // Up: towards the cameras (or world +z without any).
  Eigen::Vector3d up = best.normal;
  Eigen::Vector3d side = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d inliersMean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : inliers) inliersMean += p;
  inliersMean /= static_cast<double>(inliers.size());
  if (!cameraCentres.empty()) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& c : cameraCentres) mean += c;
    side = mean / static_cast<double>(cameraCentres.size()) - inliersMean;
  }
  if (up.dot(side) < 0) up = -up;

  ScenePlacement placement;
  placement.base = inliersMean - up * (up.dot(inliersMean) - up.dot(best.normal) * best.offset);
  Eigen::Vector3d x = Eigen::Vector3d::UnitX() - up * up.x();
  if (x.norm() < 0.3) x = Eigen::Vector3d::UnitY() - up * up.y();  // the plane faces world x
  x.normalize();
  placement.rotation.col(0) = x;
  placement.rotation.col(1) = up.cross(x);
  placement.rotation.col(2) = up;

  std::vector<double> onPlane;
  double squares = 0.0;
  for (const Eigen::Vector3d& p : inliers) {
    const Eigen::Vector3d d = p - placement.base;
    onPlane.push_back((d - up * up.dot(d)).norm());
    squares += best.distance(p) * best.distance(p);
  }
  // The edge: the inliers' median distance from the base on the plane, rounded (the desk clip,
  // references 0 and 40: 0.1 m, two and a half squares of its chessboard).
  placement.edge = roundToOneTwoFive(std::max(median(onPlane), 1e-3));
  placement.consideredPoints = static_cast<int>(near.size());
  placement.planePoints = static_cast<int>(inliers.size());
  placement.planeThresholdMetres = threshold;
  placement.planeRmsMetres = std::sqrt(squares / static_cast<double>(inliers.size()));
  return placement;
}

ScenePlacement placeOnDominantPlane(const MultiReferenceMap& map) {
  std::vector<Eigen::Vector3d> points, centres;
  for (const MapPoint& p : map.points) points.push_back(p.world);
  for (const ReferenceView& v : map.views) centres.push_back(v.T.inverse().translation());
  return placeOnDominantPlane(points, centres);
}

}  // namespace reftrack
