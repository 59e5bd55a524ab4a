#include "app/simulator/ReferencePlacement.hpp"

#include <numbers>
#include <string>

#include "app/simulator/WalkaroundArc.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/LookAt.hpp"

namespace reftrack::app {

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kFrontDeg = 15.0;  // the extra views start beyond A and B (about +-10 deg)
constexpr double kNearFactor = 0.85, kFarFactor = 1.2, kElevationStepDeg = 5.0;
}  // namespace

std::vector<RigidPose> placeReferenceViews(int count, const Eigen::Vector3d& eyeA,
                                           const Eigen::Vector3d& eyeB,
                                           const Eigen::Vector3d& target) {
  if (count < 2)
    throw Error("reference placement: at least 2 reference views, got " + std::to_string(count));
  std::vector<RigidPose> poses = {lookAtPose(eyeA, target), lookAtPose(eyeB, target)};
  const ArcPosition a = WalkaroundArc::positionOf(eyeA, target);
  const int extra = count - 2;
  const int left = (extra + 1) / 2, right = extra / 2;
  for (int j = 0; j < extra; ++j) {
    const bool onLeft = j % 2 == 0;
    const int m = onLeft ? left : right;
    const int i = j / 2 + 1;  // 1..m on its side, outwards
    ArcPosition p;
    const double azimuthDeg =
        kFrontDeg + (WalkaroundArc::kHalfSpanDeg - kFrontDeg) * static_cast<double>(i) / m;
    p.azimuthRad = (onLeft ? -1.0 : 1.0) * azimuthDeg * kDeg;
    const bool near = i % 2 == 1;
    p.distance = a.distance * (near ? kNearFactor : kFarFactor);
    p.elevationRad = a.elevationRad + (near ? -1.0 : 1.0) * kElevationStepDeg * kDeg;
    poses.push_back(lookAtPose(WalkaroundArc::eyeAt(p, target), target));
  }
  return poses;
}

}  // namespace reftrack::app
