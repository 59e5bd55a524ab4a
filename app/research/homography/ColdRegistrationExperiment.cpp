#include "app/research/homography/ColdRegistrationExperiment.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "app/cli/ProgressBar.hpp"
#include "app/research/homography/HomographyGroundTruth.hpp"
#include "app/simulator/BrickWallScene.hpp"
#include "app/simulator/ProceduralTexture.hpp"
#include "app/simulator/SensorNoise.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/homography/HomographyTracker.hpp"
#include "render/SceneRenderer.hpp"

namespace reftrack::app {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kCardWidth = 0.4, kCardHeight = 0.3;  // metres, in the plane z = 0
constexpr int kCardTexels = 2400;                      // across the card: 6 texels per mm
// The reference sees this fraction of the card's width (the card fills the frame).
constexpr double kReferenceCoverage = 0.9;
constexpr double kWallDepth = 0.5;      // the wall stands this far behind the card
constexpr double kWallSize = 6.0;       // metres, square
constexpr double kLookAtJitter = 0.04;  // metres: the look-at point is this far off centre
constexpr int kSupersample = 3;

render::TexturedMesh quad(double x0, double y0, double x1, double y1, double z, cv::Mat texture) {
  render::TexturedMesh m;
  m.positions = {Eigen::Vector3f(float(x0), float(y0), float(z)),
                 Eigen::Vector3f(float(x1), float(y0), float(z)),
                 Eigen::Vector3f(float(x1), float(y1), float(z)),
                 Eigen::Vector3f(float(x0), float(y1), float(z))};
  m.uvs = {Eigen::Vector2f(0, 0), Eigen::Vector2f(1, 0), Eigen::Vector2f(1, 1),
           Eigen::Vector2f(0, 1)};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.texture = std::move(texture);
  return m;
}

double medianOf(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

ColdBucket summarise(const std::string& label, const std::vector<const ColdTrial*>& trials,
                     double successErrorPx) {
  ColdBucket b;
  b.label = label;
  std::vector<double> errors, ms;
  for (const ColdTrial* t : trials) {
    ++b.trials;
    ms.push_back(t->milliseconds);
    if (!t->tracked) continue;
    if (t->cornerErrorPx <= successErrorPx) {
      ++b.successes;
      errors.push_back(t->cornerErrorPx);
    } else {
      ++b.wrong;
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  b.meanErrorPx = errors.empty() ? nan : 0.0;
  b.maxErrorPx = errors.empty() ? nan : 0.0;
  for (double e : errors) {
    b.meanErrorPx += e / static_cast<double>(errors.size());
    b.maxErrorPx = std::max(b.maxErrorPx, e);
  }
  b.medianMs = medianOf(ms);
  return b;
}

std::vector<ColdBucket> bucketBy(const std::vector<ColdTrial>& trials,
                                 const std::vector<double>& edges, double successErrorPx,
                                 const std::function<double(const ColdTrial&)>& key,
                                 const char* format) {
  std::vector<ColdBucket> out;
  for (size_t i = 0; i + 1 < edges.size(); ++i) {
    std::vector<const ColdTrial*> in;
    for (const ColdTrial& t : trials) {
      const double k = key(t);
      const bool last = i + 2 == edges.size();
      if (k >= edges[i] && (k < edges[i + 1] || (last && k <= edges[i + 1]))) in.push_back(&t);
    }
    char label[64];
    std::snprintf(label, sizeof label, format, edges[i], edges[i + 1]);
    out.push_back(summarise(label, in, successErrorPx));
  }
  std::vector<const ColdTrial*> all;
  for (const ColdTrial& t : trials) all.push_back(&t);
  out.push_back(summarise("all", all, successErrorPx));
  return out;
}

}  // namespace

void ColdRegistrationOptions::check() const {
  if (size.width < 64 || size.height < 48)
    throw Error("cold registration: size must be at least 64x48");
  if (!(fovDeg > 10.0 && fovDeg < 120.0))
    throw Error("cold registration: fovDeg must be in (10, 120)");
  if (trials < 1) throw Error("cold registration: trials must be at least 1");
  if (!(maxTiltDeg >= 0.0 && maxTiltDeg <= 70.0))
    throw Error("cold registration: maxTiltDeg must be in [0, 70]");
  if (!(minScale >= 0.25 && minScale <= maxScale && maxScale <= 4.0))
    throw Error("cold registration: scales must satisfy 0.25 <= minScale <= maxScale <= 4");
  if (!(noiseSigma >= 0.0 && noiseSigma <= 100.0))
    throw Error("cold registration: noiseSigma must be in [0, 100]");
  if (!(successErrorPx > 0.0)) throw Error("cold registration: successErrorPx must be positive");
  params.check();
}

std::vector<ColdTrial> runColdRegistration(const ColdRegistrationOptions& options) {
  options.check();
  const PinholeCamera camera = PinholeCamera::fromFieldOfView(options.size, options.fovDeg);
  const Eigen::Matrix3d K = camera.K();
  render::SceneRenderer renderer;
  const ProceduralTexture card(mixSeed(options.seed, 11), cv::Size2d(kCardWidth, kCardHeight));
  const ProceduralTexture wall(mixSeed(options.seed, 12), cv::Size2d(kWallSize, kWallSize));
  const int cardRows = static_cast<int>(std::lround(kCardTexels * kCardHeight / kCardWidth));
  renderer.addMesh(quad(
      -kCardWidth / 2, -kCardHeight / 2, kCardWidth / 2, kCardHeight / 2, 0.0,
      card.rasterize(cv::Rect2d(0, 0, kCardWidth, kCardHeight), cv::Size(kCardTexels, cardRows))));
  renderer.addMesh(
      quad(-kWallSize / 2, -kWallSize / 2, kWallSize / 2, kWallSize / 2, kWallDepth,
           wall.rasterize(cv::Rect2d(0, 0, kWallSize, kWallSize), cv::Size(4096, 4096))));
  // World: the card in z = 0 (x right, y down); the reference camera looks along +z at it.
  const double fx = K(0, 0);
  const double referenceDistance = fx * kCardWidth * kReferenceCoverage / options.size.width;
  const auto view = [&](const Eigen::Matrix3d& cameraToWorld, const Eigen::Vector3d& centre) {
    render::PinholeView v;
    v.K = K;
    v.imageSize = options.size;
    v.worldToCamera.setIdentity();
    v.worldToCamera.block<3, 3>(0, 0) = cameraToWorld.transpose();
    v.worldToCamera.block<3, 1>(0, 3) = -cameraToWorld.transpose() * centre;
    return v;
  };
  const render::PinholeView referenceView =
      view(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -referenceDistance));
  const cv::Matx33d referencePlane = planeToImage(K, referenceView.worldToCamera);
  const cv::Mat reference = addSensorNoise(renderer.render(referenceView, kSupersample),
                                           mixSeed(options.seed, 13), options.noiseSigma);
  HomographyTracker tracker(reference, options.params);

  std::mt19937_64 rng(mixSeed(options.seed, 14));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ColdTrial> out;
  ProgressBar progress("cold registration", static_cast<std::size_t>(options.trials), "tr");
  for (int t = 0; t < options.trials; ++t) {
    ColdTrial trial;
    trial.tiltDeg = options.maxTiltDeg * unit(rng);
    const double azimuth = 2 * kPi * unit(rng);
    trial.rollDeg = 360.0 * unit(rng);
    trial.scale = std::exp(std::log(options.minScale) +
                           (std::log(options.maxScale) - std::log(options.minScale)) * unit(rng));
    const Eigen::Vector3d lookAt(kLookAtJitter * (2 * unit(rng) - 1),
                                 kLookAtJitter * (2 * unit(rng) - 1), 0.0);
    // Camera axes: tilted by tiltDeg about the in-plane axis at `azimuth`, rolled about its own
    // optical axis; it looks at lookAt from referenceDistance / scale.
    const Eigen::Matrix3d cameraToWorld =
        Eigen::AngleAxisd(trial.tiltDeg * kPi / 180.0,
                          Eigen::Vector3d(std::cos(azimuth), std::sin(azimuth), 0.0))
            .toRotationMatrix() *
        Eigen::AngleAxisd(trial.rollDeg * kPi / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d centre =
        lookAt - (referenceDistance / trial.scale) * cameraToWorld.col(2);
    const render::PinholeView frameView = view(cameraToWorld, centre);
    cv::Matx33d truth = planeToImage(K, frameView.worldToCamera) * referencePlane.inv();
    truth *= 1.0 / truth(2, 2);
    const cv::Mat frame = addSensorNoise(
        renderer.render(frameView, kSupersample),
        mixSeed(options.seed, 1000 + static_cast<std::uint64_t>(t)), options.noiseSigma);
    tracker.reset();
    const auto t0 = std::chrono::steady_clock::now();
    const HomographyTrackResult r = tracker.track(frame);
    trial.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    trial.tracked = r.tracked;
    trial.keypointGuided = r.keypointGuided;
    trial.failure = r.failure;
    trial.cornerErrorPx = r.tracked ? frameCornerError(r.H, truth, options.size)
                                    : std::numeric_limits<double>::quiet_NaN();
    out.push_back(trial);
    progress.advance();
  }
  progress.finish();
  return out;
}

std::vector<ColdBucket> bucketByTilt(const std::vector<ColdTrial>& trials,
                                     const std::vector<double>& edges, double successErrorPx) {
  return bucketBy(
      trials, edges, successErrorPx, [](const ColdTrial& t) { return t.tiltDeg; },
      "tilt %.0f-%.0f");
}

std::vector<ColdBucket> bucketByScale(const std::vector<ColdTrial>& trials,
                                      const std::vector<double>& edges, double successErrorPx) {
  return bucketBy(
      trials, edges, successErrorPx, [](const ColdTrial& t) { return t.scale; }, "scale %.2f-%.2f");
}

}  // namespace reftrack::app
