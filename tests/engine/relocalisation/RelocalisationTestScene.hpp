#pragma once
// A relocalisation test setup on CornerWorld: an N-view map (images + poses, keypoint layer
// built by buildReferenceKeypoints; no corners or map points), and random test views whose
// viewing direction lies within 45 degrees of some reference's, at 0.5-2x its distance, with any
// roll about the optical axis.
#include <random>

#include "engine/relocalisation/CornerWorld.hpp"
#include "engine/relocalisation/ReferenceKeypointBuilder.hpp"

namespace reftrack::test {

inline constexpr double kReferenceDistanceM = 1.4;

// The N reference views alone: images and exact poses, no keypoint layer yet.
inline MultiReferenceMap cornerWorldViews(const CornerWorld& world, int views) {
  MultiReferenceMap map;
  map.camera = world.camera();
  const std::vector<RigidPose> poses = CornerWorld::referencePoses(views, kReferenceDistanceM);
  for (int i = 0; i < views; ++i) {
    ReferenceView v;
    v.name = "reference_" + std::to_string(i) + ".png";
    v.T = poses[static_cast<std::size_t>(i)];
    v.image = world.render(v.T, 10 + i);
    map.views.push_back(v);
  }
  map.poseSource = "synthetic room corner";
  return map;
}

inline MultiReferenceMap cornerWorldMap(const CornerWorld& world, int views,
                                        const RelocalisationParams& params) {
  MultiReferenceMap map = cornerWorldViews(world, views);
  buildReferenceKeypoints(map, params);
  return map;
}

// `count` random world->camera poses (seeded): a reference is drawn, its viewing direction tilted
// by up to 45 degrees (staying where all three faces are seen from the front), the distance drawn
// log-uniformly in [0.5, 2] x the reference's, the target jittered by up to 10 cm, any roll.
inline std::vector<RigidPose> randomViews(int count, int references, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const std::vector<RigidPose> refs = CornerWorld::referencePoses(references, kReferenceDistanceM);
  std::vector<RigidPose> out;
  while (static_cast<int>(out.size()) < count) {
    const RigidPose& ref = refs[static_cast<std::size_t>(rng() % refs.size())];
    const Eigen::Vector3d back = (ref.cameraCentre() - CornerWorld::centre()).normalized();
    const Eigen::Vector3d axis = back.unitOrthogonal();
    const double spin = 2.0 * M_PI * uniform(rng);
    const double tilt = 45.0 * M_PI / 180.0 * std::sqrt(uniform(rng));  // uniform on the cap
    const Eigen::Vector3d tiltAxis = Eigen::AngleAxisd(spin, back) * axis;
    const Eigen::Vector3d dir = Eigen::AngleAxisd(tilt, tiltAxis) * back;
    if (dir.minCoeff() < 0.2) continue;  // would look at a face from its edge or behind it
    const double distance =
        kReferenceDistanceM * std::exp(std::log(0.5) + std::log(4.0) * uniform(rng));
    const Eigen::Vector3d target =
        CornerWorld::centre() +
        0.1 * Eigen::Vector3d(2 * uniform(rng) - 1, 2 * uniform(rng) - 1, 2 * uniform(rng) - 1);
    out.push_back(
        CornerWorld::lookAt(target + distance * dir, target, 360.0 * uniform(rng) - 180.0));
  }
  return out;
}

}  // namespace reftrack::test
