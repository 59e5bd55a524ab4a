#include "engine/tracking/ReferenceSelector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

double median(std::vector<double> values) {
  const auto mid = values.begin() + static_cast<long>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

}  // namespace

ReferenceSelector::ReferenceSelector(const MultiReferenceMap& map, ReferenceSelectionParams params)
    : params_(params), views_(map.size()) {
  params_.check();
  const std::size_t n = static_cast<std::size_t>(views_);
  for (const ReferenceView& v : map.views) {
    centres_.push_back(v.T.cameraCentre());
    directions_.push_back(v.T.rotation().row(2).transpose());  // optical axis in the world
  }
  // Shared points of every pair in one pass over the points (MultiReferenceMap::sharedPoints
  // per pair would pass over them N^2 / 2 times). Depths of each view's points on the way.
  shared_.assign(n * n, 0);
  std::vector<std::vector<double>> depths(n);
  for (const MapPoint& p : map.points) {
    for (std::size_t i = 0; i < p.observations.size(); ++i) {
      const int a = p.observations[i].view;
      if (a < 0 || a >= views_)
        throw Error("ReferenceSelector: a map point names view " + std::to_string(a) + " of " +
                    std::to_string(views_));
      depths[static_cast<std::size_t>(a)].push_back(
          (map.views[static_cast<std::size_t>(a)].T * p.world).z());
      for (std::size_t j = i + 1; j < p.observations.size(); ++j) {
        const int b = p.observations[j].view;
        if (b < 0 || b >= views_ || b == a) continue;
        ++shared_[static_cast<std::size_t>(a) * n + static_cast<std::size_t>(b)];
        ++shared_[static_cast<std::size_t>(b) * n + static_cast<std::size_t>(a)];
      }
    }
  }
  std::vector<double> viewDepths;
  for (const std::vector<double>& d : depths)
    if (!d.empty()) viewDepths.push_back(median(d));
  if (!viewDepths.empty()) sceneDepth_ = median(viewDepths);
  // Degenerate depths (points behind the references) fall back to 1 map unit; the map's own
  // check reports such maps, the selector only needs a scale.
  if (!(sceneDepth_ > 0.0) || !std::isfinite(sceneDepth_)) sceneDepth_ = 1.0;
  partners_.resize(n);
  for (int a = 0; a < views_; ++a)
    for (int b = a + 1; b < views_; ++b)
      if (sharedPoints(a, b) >= params_.minSharedPoints) {
        candidates_.push_back({a, b});
        partners_[static_cast<std::size_t>(a)].push_back(b);
        partners_[static_cast<std::size_t>(b)].push_back(a);
      }
  // A two-reference map has one pair: it is used whatever it shares (the map was made for it).
  if (candidates_.empty() && views_ == 2) {
    candidates_.push_back({0, 1});
    partners_[0].push_back(1);
    partners_[1].push_back(0);
  }
  if (candidates_.empty())
    throw Error("no pair of the map's " + std::to_string(views_) + " references shares " +
                std::to_string(params_.minSharedPoints) +
                " map points (references.min_shared_points)");
}

int ReferenceSelector::sharedPoints(int a, int b) const {
  if (a < 0 || b < 0 || a >= views_ || b >= views_) return 0;
  return shared_[static_cast<std::size_t>(a) * static_cast<std::size_t>(views_) +
                 static_cast<std::size_t>(b)];
}

double ReferenceSelector::referenceCost(int view, const RigidPose& worldToCamera) const {
  const std::size_t v = static_cast<std::size_t>(view);
  const Eigen::Vector3d direction = worldToCamera.rotation().row(2).transpose();
  const double cosAngle = std::clamp(direction.dot(directions_[v]), -1.0, 1.0);
  return (worldToCamera.cameraCentre() - centres_[v]).norm() / sceneDepth_ +
         params_.angleWeight * std::acos(cosAngle);
}

double ReferenceSelector::pairCost(ReferencePair pair, const RigidPose& worldToCamera) const {
  return referenceCost(pair.a, worldToCamera) + referenceCost(pair.b, worldToCamera);
}

ReferencePair ReferenceSelector::best(const RigidPose& worldToCamera) const {
  std::vector<double> cost(static_cast<std::size_t>(views_));
  for (int v = 0; v < views_; ++v)
    cost[static_cast<std::size_t>(v)] = referenceCost(v, worldToCamera);
  std::vector<int> order(static_cast<std::size_t>(views_));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int x, int y) {
    return cost[static_cast<std::size_t>(x)] < cost[static_cast<std::size_t>(y)];
  });
  ReferencePair bestPair;
  double bestCost = std::numeric_limits<double>::infinity();
  for (const int a : order) {
    const double ca = cost[static_cast<std::size_t>(a)];
    // Every pair not seen yet has both references at least as costly as a.
    if (2.0 * ca >= bestCost) break;
    for (const int b : partners_[static_cast<std::size_t>(a)]) {
      const double c = ca + cost[static_cast<std::size_t>(b)];
      if (c < bestCost) {
        bestCost = c;
        bestPair = {std::min(a, b), std::max(a, b)};
      }
    }
  }
  return bestPair;
}

ReferencePair ReferenceSelector::select(const RigidPose& predictedWorldToCamera) {
  const ReferencePair cheapest = best(predictedWorldToCamera);
  if (!current_.valid() || cheapest == current_) {
    current_ = cheapest;
    pending_ = {};
    pendingFrames_ = 0;
    return current_;
  }
  const double inUse = pairCost(current_, predictedWorldToCamera);
  const double other = pairCost(cheapest, predictedWorldToCamera);
  if (other < (1.0 - params_.switchMargin) * inUse) {
    pendingFrames_ = cheapest == pending_ ? pendingFrames_ + 1 : 1;
    pending_ = cheapest;
    if (pendingFrames_ >= params_.switchAfterFrames) {
      current_ = cheapest;
      pending_ = {};
      pendingFrames_ = 0;
    }
  } else {
    pending_ = {};
    pendingFrames_ = 0;
  }
  return current_;
}

void ReferenceSelector::setCurrent(ReferencePair pair) {
  if (!pair.valid() || pair.a >= views_ || pair.b >= views_ || pair.a >= pair.b)
    throw Error("ReferenceSelector: (" + std::to_string(pair.a) + ", " + std::to_string(pair.b) +
                ") is not a pair of references a < b of " + std::to_string(views_));
  current_ = pair;
  pending_ = {};
  pendingFrames_ = 0;
}

void ReferenceSelector::reset() {
  current_ = {};
  pending_ = {};
  pendingFrames_ = 0;
}

}  // namespace reftrack
