#pragma once
// WalkaroundArc: the volume the `walkaround` preset walks through and the extra reference cameras
// are placed in. A camera on the arc sits at azimuth `azimuth` about the vertical through the
// looked-at point (0 = in front of the desk, on the -y side; positive towards +x), `distance`
// metres from it, `elevation` above its horizontal plane, and looks at it. Reference view A of
// the desk scene is such a camera (about -9.8 deg, 1.0 m, 43 deg).
#include <Eigen/Core>

namespace reftrack::app {

struct ArcPosition {
  double azimuthRad = 0.0;
  double distance = 1.0;  // metres
  double elevationRad = 0.0;
};

struct WalkaroundArc {
  // The walk sweeps +-65 deg (130 deg in all), at 1/1.65 .. 1.65 times A's distance
  // (0.60 .. 1.65 m), A's elevation +-10 deg: it stays inside the desk's walls (|x|, y < 0.95 m)
  // and above the desk everywhere.
  static constexpr double kHalfSpanDeg = 65.0;
  static constexpr double kDistanceFactor = 1.65;
  static constexpr double kElevationSwingDeg = 10.0;

  // Where `eye` is relative to `target`.
  static ArcPosition positionOf(const Eigen::Vector3d& eye, const Eigen::Vector3d& target);
  // The eye at `position` relative to `target`.
  static Eigen::Vector3d eyeAt(const ArcPosition& position, const Eigen::Vector3d& target);
};

}  // namespace reftrack::app
