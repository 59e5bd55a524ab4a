#include "app/simulator/WalkaroundArc.hpp"

#include <cmath>

namespace reftrack::app {

ArcPosition WalkaroundArc::positionOf(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  const Eigen::Vector3d d = eye - target;
  ArcPosition p;
  p.distance = d.norm();
  p.azimuthRad = std::atan2(d.x(), -d.y());
  p.elevationRad = std::atan2(d.z(), std::hypot(d.x(), d.y()));
  return p;
}

Eigen::Vector3d WalkaroundArc::eyeAt(const ArcPosition& p, const Eigen::Vector3d& target) {
  const double horizontal = p.distance * std::cos(p.elevationRad);
  return target + Eigen::Vector3d(horizontal * std::sin(p.azimuthRad),
                                  -horizontal * std::cos(p.azimuthRad),
                                  p.distance * std::sin(p.elevationRad));
}

}  // namespace reftrack::app
