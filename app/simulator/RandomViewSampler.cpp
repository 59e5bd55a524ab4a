#include "app/simulator/RandomViewSampler.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <string>

#include "app/simulator/SensorNoise.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/LookAt.hpp"

namespace reftrack::app {

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr int kMaxDraws = 10000;
}  // namespace

void RandomViewParams::check() const {
  if (!(maxAngleDeg >= 0.0 && maxAngleDeg < 90.0))
    throw Error("random views: maxAngleDeg must be in [0, 90)");
  if (!(minDistanceRatio > 0.0 && maxDistanceRatio >= minDistanceRatio &&
        std::isfinite(maxDistanceRatio)))
    throw Error("random views: minDistanceRatio must be > 0 and <= maxDistanceRatio");
  if (!(maxRollDeg >= 0.0 && maxRollDeg <= 180.0))
    throw Error("random views: maxRollDeg must be in [0, 180]");
  if (!(roomHalfSide > 0.0 && std::isfinite(roomHalfSide)))
    throw Error("random views: roomHalfSide must be positive");
  if (!std::isfinite(minHeight)) throw Error("random views: minHeight must be finite");
}

RandomViewSampler::RandomViewSampler(std::vector<RigidPose> references,
                                     const Eigen::Vector3d& target, std::uint64_t seed,
                                     RandomViewParams params)
    : references_(std::move(references)),
      target_(target),
      params_(params),
      rng_(mixSeed(seed, 0x52414E44564945ull)) {
  params_.check();
  if (references_.empty()) throw Error("random views: no reference views");
  for (const RigidPose& r : references_)
    if (!((r.cameraCentre() - target_).norm() > 1e-6))
      throw Error("random views: a reference camera sits on the target");
}

SampledView RandomViewSampler::next() {
  for (int draw = 0; draw < kMaxDraws; ++draw) {
    SampledView v;
    v.reference = rng_.uniform(0, static_cast<int>(references_.size()));
    const RigidPose& ref = references_[static_cast<std::size_t>(v.reference)];
    const Eigen::Vector3d toEye = ref.cameraCentre() - target_;
    const Eigen::Vector3d axis = toEye.normalized();
    // Uniform over the cap: cos(angle) uniform in [cos(max), 1], azimuth about the axis uniform.
    const double cosAngle = rng_.uniform(std::cos(params_.maxAngleDeg * kDeg), 1.0);
    const double angle = std::acos(std::min(1.0, cosAngle));
    const double spin = rng_.uniform(0.0, 2.0 * std::numbers::pi);
    const Eigen::Vector3d side = axis.unitOrthogonal();
    const Eigen::Vector3d tiltAxis = Eigen::AngleAxisd(spin, axis) * side;
    const Eigen::Vector3d direction = Eigen::AngleAxisd(angle, tiltAxis) * axis;
    v.distanceRatio = std::exp(
        rng_.uniform(std::log(params_.minDistanceRatio), std::log(params_.maxDistanceRatio)));
    const Eigen::Vector3d eye = target_ + v.distanceRatio * toEye.norm() * direction;
    if (std::abs(eye.x()) > params_.roomHalfSide || eye.y() > params_.roomHalfSide ||
        eye.z() < params_.minHeight)
      continue;
    // Nearly vertical views have no "up": draw again.
    if (std::abs(direction.z()) > 0.999) continue;
    v.rollDeg = rng_.uniform(-params_.maxRollDeg, params_.maxRollDeg);
    const RigidPose roll(
        Eigen::AngleAxisd(v.rollDeg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
        Eigen::Vector3d::Zero());
    v.worldToCamera = roll * lookAtPose(eye, target_);
    v.angleDeg = angle / kDeg;
    return v;
  }
  throw Error("random views: " + std::to_string(kMaxDraws) +
              " draws in a row left the room; widen roomHalfSide or lower minHeight");
}

}  // namespace reftrack::app
