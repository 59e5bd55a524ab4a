#pragma once
// RandomViewSampler: random camera poses in the volume mapped by a set of reference views, for
// cold-start and relocalisation trials. Each view picks a reference at random, a viewing
// direction within maxAngleDeg of that reference's (uniform over the spherical cap about the
// direction from `target` to the reference's eye), a distance to `target` of minDistanceRatio ..
// maxDistanceRatio times the reference's (log-uniform), looks at `target` and turns about its
// optical axis by a uniform roll in [-maxRollDeg, maxRollDeg]. Eyes outside the desk scene's
// room (|x| or y beyond roomHalfSide, below minHeight: the boxes stand up to 0.3 m) are drawn
// again. Deterministic in the seed.
#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "engine/geometry/RigidPose.hpp"

namespace reftrack::app {

struct RandomViewParams {
  double maxAngleDeg = 45.0;
  double minDistanceRatio = 0.5, maxDistanceRatio = 2.0;
  double maxRollDeg = 180.0;
  double roomHalfSide = 0.95;  // metres; walls at +-1 m (x) and +1 m (y)
  double minHeight = 0.35;     // metres above the desk
  void check() const;          // throws reftrack::Error naming the bad field
};

struct SampledView {
  RigidPose worldToCamera;
  int reference = -1;          // the reference it was drawn about
  double angleDeg = 0.0;       // between its optical axis and the reference's
  double distanceRatio = 1.0;  // its distance to the target over the reference's
  double rollDeg = 0.0;
};

class RandomViewSampler {
 public:
  // `references`: world->camera poses, each looking at `target`. Throws reftrack::Error when
  // there are none or params are bad.
  RandomViewSampler(std::vector<RigidPose> references, const Eigen::Vector3d& target,
                    std::uint64_t seed, RandomViewParams params = {});
  SampledView next();  // throws reftrack::Error when 10000 draws in a row leave the room

 private:
  std::vector<RigidPose> references_;
  Eigen::Vector3d target_;
  RandomViewParams params_;
  cv::RNG rng_;
};

}  // namespace reftrack::app
