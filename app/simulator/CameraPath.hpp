#pragma once
// CameraPath: the exact world->camera pose of each simulated frame, as a smooth function of the
// continuous frame time s (frame k at s = k; motion blur samples s in [k - 1/2, k + 1/2]).
// Reference view A is a camera at `eye` looking at `target`; all presets but forward start there:
//   handheld  slow seeded wandering (up to ~0.3 m, ~20 deg) plus hand shake, back near A at the end
//   orbit     arc of +-75 deg about the vertical through `target`, always looking at it
//   rotate    pure rotation about A's optical centre: yaw +-40 deg about the vertical, small pitch
//   static    A throughout
//   forward   along A's line of sight from 2 m to 0.6 m from `target`
//   walkaround  around `target` on the WalkaroundArc: azimuth +-65 deg (130 deg span, out and
//             back through A), distance 0.60-1.65 m, elevation A's +-10 deg, looking at points
//             within 4 cm of `target`, plus the handheld tremor; starts and ends at A
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "app/simulator/SimulationOptions.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack::app {

class CameraPath {
 public:
  // Uses options.preset, frames, fps and seed (seed drives the handheld wandering and shake).
  CameraPath(const SimulationOptions& options, const Eigen::Vector3d& eye,
             const Eigen::Vector3d& target);

  RigidPose at(double frameTime) const;  // world->camera
  RigidPose start() const;               // reference view A

 private:
  // Sum of sinusoids a_i sin(2 pi f_i t + phi_i), t in seconds.
  struct Wave {
    std::vector<std::array<double, 3>> terms;  // {amplitude, frequency Hz, phase}
    double operator()(double t) const;
  };
  RigidPose handheld(double s) const;
  RigidPose walkaround(double s) const;
  RigidPose tremor(double s) const;  // hand shake, fading in over the first frames
  double progress(double s) const;   // s / (frames - 1); 0 for a single frame

  std::string preset_;
  int frames_;
  double fps_;
  Eigen::Vector3d eye_, target_;
  std::vector<Wave> wander_;  // eye x,y,z (m), target x,y,z (m), roll (rad); scaled to amplitude
  std::vector<Wave> shake_;   // camera-frame rotation x,y,z (rad), translation x,y,z (m)
};

}  // namespace reftrack::app
