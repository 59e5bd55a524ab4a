#pragma once
// ReferenceSelector (issue 13): which two references of a MultiReferenceMap the 6-DOF tracker
// runs on for a predicted camera pose. A reference costs the distance between its camera centre
// and the camera's divided by the scene depth, plus angleWeight times the angle between their
// viewing directions; a pair costs the sum of its two, and only pairs sharing at least
// minSharedPoints map points are candidates (counted once, at construction; a two-reference map's
// one pair always is). select() adds
// hysteresis: it leaves the pair in use only for one cheaper by switchMargin (relative) on
// switchAfterFrames consecutive frames. Per frame O(N) plus a scan of the candidate pairs that
// stops as soon as no cheaper pair can follow.
#include <utility>
#include <vector>

#include "engine/config/ReferenceSelectionParams.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack {

// Two references, a < b (the pair's tracker takes a as V_A, b as V_B); (-1, -1) = none.
struct ReferencePair {
  int a = -1, b = -1;
  bool valid() const { return a >= 0 && b >= 0; }
  bool operator==(const ReferencePair&) const = default;
};

class ReferenceSelector {
 public:
  // Throws reftrack::Error when no pair of the map shares minSharedPoints map points.
  ReferenceSelector(const MultiReferenceMap& map, ReferenceSelectionParams params);

  // The cheapest candidate pair for this world->camera pose (no hysteresis).
  ReferencePair best(const RigidPose& worldToCamera) const;
  // The pair to use this frame, with hysteresis against the pair in use.
  ReferencePair select(const RigidPose& predictedWorldToCamera);
  // Makes `pair` the pair in use (after a relocalisation or a failed hand-over).
  void setCurrent(ReferencePair pair);
  ReferencePair current() const { return current_; }
  void reset();  // no pair in use

  double referenceCost(int view, const RigidPose& worldToCamera) const;
  double pairCost(ReferencePair pair, const RigidPose& worldToCamera) const;
  int sharedPoints(int a, int b) const;  // from the table built at construction
  const std::vector<ReferencePair>& candidatePairs() const { return candidates_; }
  double sceneDepth() const { return sceneDepth_; }

 private:
  ReferenceSelectionParams params_;
  int views_ = 0;
  std::vector<Eigen::Vector3d> centres_, directions_;  // world frame
  double sceneDepth_ = 1.0;
  std::vector<int> shared_;                 // views_ x views_
  std::vector<std::vector<int>> partners_;  // candidate partners of each view
  std::vector<ReferencePair> candidates_;
  ReferencePair current_, pending_;
  int pendingFrames_ = 0;
};

}  // namespace reftrack
