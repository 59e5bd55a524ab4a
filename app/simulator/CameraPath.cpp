#include "app/simulator/CameraPath.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>

#include "app/simulator/SensorNoise.hpp"
#include "app/simulator/WalkaroundArc.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/LookAt.hpp"

namespace reftrack::app {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

// Handheld wandering: peak offsets reached somewhere along the path (world frame, metres), then
// the roll about the optical axis (radians). Eye x is sideways, y along the desk, z height.
constexpr std::array<double, 7> kWanderAmplitude = {0.22, 0.12, 0.12, 0.06, 0.05, 0.03, 4.0 * kDeg};
// Hand shake: standard deviations of a 1.5-7 Hz tremor (rotation rad, translation m).
constexpr double kShakeRotationSd = 0.12 * kDeg;
constexpr double kShakeTranslationSd = 0.0008;
// Orbit half-arc and height swing; rotate yaw and pitch; forward start and end distance.
constexpr double kOrbitArc = 75.0 * kDeg, kOrbitHeightSwing = 0.08;
constexpr double kRotateYaw = 40.0 * kDeg, kRotatePitch = 6.0 * kDeg;
constexpr double kForwardFrom = 2.0, kForwardTo = 0.6;

RigidPose rotationAboutCentre(const RigidPose& worldToCamera, const Eigen::Matrix3d& worldTurn,
                              const Eigen::Matrix3d& cameraTurn) {
  // Camera->world rotation turned by `worldTurn` in the world and `cameraTurn` in the camera
  // frame; the optical centre stays where it is.
  const Eigen::Vector3d centre = worldToCamera.cameraCentre();
  const Eigen::Matrix3d R =
      cameraTurn.transpose() * worldToCamera.rotation() * worldTurn.transpose();
  return RigidPose(R, -R * centre);
}

}  // namespace

double CameraPath::Wave::operator()(double t) const {
  double v = 0.0;
  for (const auto& [a, f, phi] : terms) v += a * std::sin(2.0 * kPi * f * t + phi);
  return v;
}

CameraPath::CameraPath(const SimulationOptions& options, const Eigen::Vector3d& eye,
                       const Eigen::Vector3d& target)
    : preset_(options.preset),
      frames_(options.frames),
      fps_(options.fps),
      eye_(eye),
      target_(target) {
  options.check();
  lookAtPose(eye, target);  // throws on a degenerate view
  cv::RNG rng(mixSeed(options.seed, 0x7061746870617468ull));
  auto randomWave = [&](int terms, double fLow, double fHigh) {
    Wave w;
    for (int i = 0; i < terms; ++i)
      w.terms.push_back(
          {rng.uniform(0.5, 1.0), rng.uniform(fLow, fHigh), rng.uniform(0.0, 2.0 * kPi)});
    return w;
  };
  for (double amplitude : kWanderAmplitude) {
    Wave w = randomWave(3, 0.04, 0.3);
    // Scale so the enveloped wave peaks at `amplitude` over the frames actually rendered.
    double peak = 0.0;
    for (int k = 0; k < frames_; ++k)
      peak = std::max(peak, std::abs(std::sin(kPi * progress(k)) * w(k / fps_)));
    const double scale = peak > 1e-12 ? amplitude / peak : 0.0;
    for (auto& term : w.terms) term[0] *= scale;
    wander_.push_back(w);
  }
  for (int axis = 0; axis < 6; ++axis) {
    Wave w = randomWave(4, 1.5, 7.0);
    double power = 0.0;  // variance of a sum of sinusoids: sum a^2 / 2
    for (const auto& term : w.terms) power += 0.5 * term[0] * term[0];
    const double sd = axis < 3 ? kShakeRotationSd : kShakeTranslationSd;
    for (auto& term : w.terms) term[0] *= sd / std::sqrt(power);
    shake_.push_back(w);
  }
}

double CameraPath::progress(double s) const { return frames_ > 1 ? s / (frames_ - 1) : 0.0; }

RigidPose CameraPath::start() const { return lookAtPose(eye_, target_); }

RigidPose CameraPath::handheld(double s) const {
  const double t = s / fps_;
  const double envelope = std::sin(kPi * progress(s));
  Eigen::Vector3d eye = eye_, target = target_;
  for (int i = 0; i < 3; ++i) {
    eye[i] += envelope * wander_[i](t);
    target[i] += envelope * wander_[3 + i](t);
  }
  const double roll = envelope * wander_[6](t);
  const RigidPose smooth =
      RigidPose(Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
                Eigen::Vector3d::Zero()) *
      lookAtPose(eye, target);
  return tremor(s) * smooth;
}

RigidPose CameraPath::tremor(double s) const {
  // The tremor fades in over the first frames so frame 0 is exactly view A.
  const double t = s / fps_;
  const double shakeGain = s > 0.0 ? 1.0 - std::exp(-s / 4.0) : 0.0;
  Vector6d shake;
  for (int i = 0; i < 6; ++i) shake[i] = shakeGain * shake_[i](t);
  const Vector6d tremor =
      (Vector6d() << shake[3], shake[4], shake[5], shake[0], shake[1], shake[2]).finished();
  return RigidPose::fromVector6(tremor);
}

RigidPose CameraPath::walkaround(double s) const {
  const double u = progress(s);
  const ArcPosition a = WalkaroundArc::positionOf(eye_, target_);
  const double halfSpan = WalkaroundArc::kHalfSpanDeg * kDeg;
  // Azimuth: one full sine period whose phase puts u = 0 (and u = 1) at A's azimuth.
  const double phase = std::asin(std::clamp(a.azimuthRad / halfSpan, -1.0, 1.0));
  ArcPosition p;
  p.azimuthRad = halfSpan * std::sin(2.0 * kPi * u + phase);
  // Distance: two periods (far, near, far, near) on a log scale about A's distance.
  p.distance = a.distance * std::pow(WalkaroundArc::kDistanceFactor, std::sin(4.0 * kPi * u));
  p.elevationRad =
      a.elevationRad + WalkaroundArc::kElevationSwingDeg * kDeg * std::sin(6.0 * kPi * u);
  // Looked-at point: wanders within 4 cm of the target ("roughly at the scene").
  const Eigen::Vector3d target =
      target_ + 0.023 * Eigen::Vector3d(std::sin(5.0 * kPi * u), std::sin(7.0 * kPi * u),
                                        std::sin(3.0 * kPi * u));
  return tremor(s) * lookAtPose(WalkaroundArc::eyeAt(p, target_), target);
}

RigidPose CameraPath::at(double s) const {
  if (!std::isfinite(s)) throw Error("camera path: frame time is not finite");
  const double u = progress(s);
  if (preset_ == "static") return start();
  if (preset_ == "handheld") return handheld(s);
  if (preset_ == "walkaround") return walkaround(s);
  if (preset_ == "orbit") {
    const double angle = kOrbitArc * std::sin(2.0 * kPi * u);
    Eigen::Vector3d eye =
        target_ + Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()) * (eye_ - target_);
    eye.z() += kOrbitHeightSwing * std::sin(4.0 * kPi * u);
    return lookAtPose(eye, target_);
  }
  if (preset_ == "rotate") {
    const double yaw = kRotateYaw * std::sin(2.0 * kPi * u);
    const double pitch = kRotatePitch * std::sin(4.0 * kPi * u);
    return rotationAboutCentre(
        start(), Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
        Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()).toRotationMatrix());
  }
  if (preset_ == "forward") {
    const double ease = u * u * (3.0 - 2.0 * u);
    const double distance = kForwardFrom + (kForwardTo - kForwardFrom) * ease;
    return lookAtPose(target_ + distance * (eye_ - target_).normalized(), target_);
  }
  throw Error("camera path: unknown preset '" + preset_ + "'");
}

}  // namespace reftrack::app
