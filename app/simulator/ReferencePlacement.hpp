#pragma once
// placeReferenceViews: the world->camera poses of a simulation's reference views. The first two
// are always the desk scene's references A and B (so two-reference users see what they always
// did); views 2.. lie on the WalkaroundArc, alternating left (-azimuth) and right, outwards from
// the front: a side holding m of them has them at 15 + 50 i / m deg (i = 1..m, the last at the
// arc's end, 65 deg), alternately nearer (0.85x A's distance, 5 deg lower) and farther (1.2x,
// 5 deg higher) — inside the volume the walkaround preset walks through.
#include <Eigen/Core>
#include <vector>

#include "engine/geometry/RigidPose.hpp"

namespace reftrack::app {

// Throws reftrack::Error when count < 2.
std::vector<RigidPose> placeReferenceViews(int count, const Eigen::Vector3d& eyeA,
                                           const Eigen::Vector3d& eyeB,
                                           const Eigen::Vector3d& target);

}  // namespace reftrack::app
