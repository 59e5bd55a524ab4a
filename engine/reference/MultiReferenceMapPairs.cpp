// MultiReferenceMap: the pair view, the measured pixels and the conversion from a two-reference
// map.
#include <algorithm>
#include <string>

#include "engine/core/Error.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack {

namespace {

const PointObservation* observationIn(const MapPoint& p, int view) {
  for (const PointObservation& o : p.observations)
    if (o.view == view) return &o;
  return nullptr;
}

int cornerIn(const MapPoint& p, int view) {
  const PointObservation* o = observationIn(p, view);
  return o ? o->corner : -1;
}

}  // namespace

ReferenceMap MultiReferenceMap::pair(int a, int b) const {
  const int n = size();
  if (a < 0 || b < 0 || a >= n || b >= n || a == b)
    throw Error("reference pair (" + std::to_string(a) + ", " + std::to_string(b) +
                ") is not two different references of " + std::to_string(n));
  const ReferenceView& va = views[static_cast<std::size_t>(a)];
  const ReferenceView& vb = views[static_cast<std::size_t>(b)];
  ReferenceMap m;
  m.camera = camera;
  m.T_A = va.T;
  m.T_B = vb.T;
  m.imageA = va.image;
  m.imageB = vb.image;
  m.cornersA = va.corners;
  m.cornersB = vb.corners;
  m.poseSource = poseSource;
  m.preparationParams = preparationParams;
  m.denserCorners = denserCorners;
  for (const MapPoint& p : points) {
    const PointObservation *oa = observationIn(p, a), *ob = observationIn(p, b);
    if (!oa || !ob) continue;
    const Eigen::Vector3d inA = va.T * p.world;
    if (!(inA.z() > 0.0)) continue;
    m.matches.push_back({oa->corner, ob->corner, inA, oa->peak, ob->peak});
  }
  return m;
}

int MultiReferenceMap::sharedPoints(int a, int b) const {
  return static_cast<int>(std::count_if(points.begin(), points.end(), [&](const MapPoint& p) {
    return cornerIn(p, a) >= 0 && cornerIn(p, b) >= 0;
  }));
}

MultiReferenceMap MultiReferenceMap::fromPair(const ReferenceMap& map) {
  MultiReferenceMap m;
  m.camera = map.camera;
  m.poseSource = map.poseSource;
  m.preparationParams = map.preparationParams;
  m.denserCorners = map.denserCorners;
  m.views.resize(2);
  m.views[0] = ReferenceView{"reference_a.png", map.T_A, true, map.imageA, map.cornersA, {}};
  m.views[1] = ReferenceView{"reference_b.png", map.T_B, true, map.imageB, map.cornersB, {}};
  const RigidPose AtoWorld = map.T_A.inverse();
  for (const ReferenceMatch& match : map.matches)
    m.points.push_back(
        MapPoint{AtoWorld * match.pointA,
                 {{0, match.cornerA, match.peakA}, {1, match.cornerB, match.peakB}}});
  return m;
}

cv::Point2f MultiReferenceMap::measuredPixel(const PointObservation& o) const {
  if (o.peak) return *o.peak;
  return views[static_cast<std::size_t>(o.view)].corners[static_cast<std::size_t>(o.corner)].pixel;
}

}  // namespace reftrack
