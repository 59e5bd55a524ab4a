#include "app/research/homography/RotationSweepExperiment.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "app/cli/ProgressBar.hpp"
#include "app/research/homography/HomographyGroundTruth.hpp"
#include "app/research/homography/StaticHomographyExperiment.hpp"
#include "app/simulator/CameraEffectsPipeline.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "app/simulator/SensorNoise.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/FrameUndistorter.hpp"
#include "engine/homography/HomographyDlt.hpp"
#include "engine/homography/HomographyTracker.hpp"

namespace reftrack::app {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Annotations: a 9 x 7 grid over the reference (every part of the image, like real labels).
constexpr int kGridCols = 9, kGridRows = 7;

// True when H draws an annotation inside the frame that the camera does not see (its true image
// lies outside), farther than `tolerance` from where it truly is: a registration that is right
// on the overlap but extrapolates wildly beyond it would show labels that are not there.
bool placesHiddenAnnotation(const cv::Matx33d& H, const cv::Matx33d& trueH,
                            const std::vector<cv::Point2d>& points, cv::Size size,
                            double tolerance) {
  const auto inside = [&](cv::Point2d q) {
    return std::isfinite(q.x) && std::isfinite(q.y) && q.x >= 0 && q.y >= 0 && q.x < size.width &&
           q.y < size.height;
  };
  for (const cv::Point2d& p : points) {
    const cv::Point2d truth = transferPoint(trueH, p), drawn = transferPoint(H, p);
    if (!inside(truth) && inside(drawn) && cv::norm(drawn - truth) > tolerance) return true;
  }
  return false;
}

double medianOf(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

void RotationSweepOptions::check() const {
  if (size.width < 64 || size.height < 48)
    throw Error("rotation sweep: size must be at least 64x48");
  if (!(fovDeg > 1.0 && fovDeg < 170.0)) throw Error("rotation sweep: fovDeg must be in (1, 170)");
  if (!(maxAngleDeg >= 0.0 && maxAngleDeg <= 90.0))
    throw Error("rotation sweep: maxAngleDeg must be in [0, 90]");
  if (!(stepDeg > 0.0)) throw Error("rotation sweep: stepDeg must be positive");
  if (trials < 1) throw Error("rotation sweep: trials must be at least 1");
  if (!(successErrorPx > 0.0)) throw Error("rotation sweep: successErrorPx must be positive");
  if (!(noiseSigma >= 0.0 && noiseSigma <= 100.0))
    throw Error("rotation sweep: noiseSigma must be in [0, 100]");
  params.check();
  effects.check();
}

std::vector<RotationStep> runRotationSweep(const RotationSweepOptions& options) {
  options.check();
  SimulationOptions sim = staticViewSimulation(options.size, options.fovDeg, options.seed,
                                               options.noiseSigma, options.effects);
  sim.distortion = options.distortion;
  SceneSimulator simulator(sim);
  const CameraEffectsPipeline camera(
      options.effects, CameraSetup{options.size, 30.0, 1, options.seed, options.noiseSigma},
      [](double) { return cv::Mat(); });
  const auto still = [&](const cv::Mat& clean, std::uint64_t seed) {
    return options.effects.any() ? camera.still(clean, seed)
                                 : addSensorNoise(clean, seed, options.noiseSigma);
  };
  const Eigen::Matrix3d K = simulator.camera().K();
  const FrameUndistorter undistorter(simulator.camera());
  const RigidPose poseA = simulator.referencePoseA();
  const cv::Mat cleanReference = simulator.renderView(poseA, 0, 0.0);
  const std::vector<cv::Point2d> annotations = annotationGrid(options.size, kGridCols, kGridRows);

  const int steps = static_cast<int>(std::floor(options.maxAngleDeg / options.stepDeg + 1e-9)) + 1;
  std::vector<RotationStep> out;
  ProgressBar progress("rotation sweep", static_cast<std::size_t>(steps * options.trials), "tr");
  for (int s = 0; s < steps; ++s) {
    RotationStep step;
    step.angleDeg = s * options.stepDeg;
    // Pan about the camera's vertical axis (image y), left and right: X_frame = R X_ref.
    cv::Mat clean[2];
    cv::Matx33d trueH[2];
    for (int side = 0; side < 2; ++side) {
      const double angle = (side == 0 ? 1.0 : -1.0) * step.angleDeg * kPi / 180.0;
      const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).matrix();
      clean[side] = simulator.renderView(RigidPose(R, Eigen::Vector3d::Zero()) * poseA, 0, 0.0);
      trueH[side] = rotationHomography(K, R);
      step.overlap += 0.5 * overlapFraction(trueH[side], options.size);
    }
    std::vector<double> errors, ms;
    for (int t = 0; t < options.trials; ++t) {
      const int side = t % 2;
      const std::uint64_t trialSeed =
          mixSeed(options.seed, static_cast<std::uint64_t>(s) * 100003u + t);
      const cv::Mat reference = undistorter.undistort(still(cleanReference, mixSeed(trialSeed, 1)));
      const cv::Mat frame = undistorter.undistort(still(clean[side], mixSeed(trialSeed, 2)));
      ++step.trials;
      try {
        HomographyTracker tracker(
            reference, options.params,
            options.calibrated ? std::optional<Eigen::Matrix3d>(K) : std::nullopt);
        const auto t0 = std::chrono::steady_clock::now();
        const HomographyTrackResult r = tracker.track(frame);
        ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count());
        if (r.tracked) {
          // NaN when no annotation lies inside the frame: nothing to check, so not a success.
          const double e = meanTransferDeviation(r.H, trueH[side], annotations, options.size);
          if (e < options.successErrorPx &&
              !placesHiddenAnnotation(r.H, trueH[side], annotations, options.size,
                                      options.successErrorPx)) {
            ++step.successes;
            if (r.rotationModel) ++step.rotationModelSuccesses;
            errors.push_back(e);
          } else {
            ++step.trackedButWrong;
          }
        }
      } catch (const Error&) {
        // A reference without enough corners cannot be registered: the trial fails.
      }
      progress.advance();
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    step.meanErrorPx = nan;
    step.maxErrorPx = nan;
    if (!errors.empty()) {
      double sum = 0, worst = 0;
      for (double e : errors) {
        sum += e;
        worst = std::max(worst, e);
      }
      step.meanErrorPx = sum / static_cast<double>(errors.size());
      step.maxErrorPx = worst;
    }
    step.medianErrorPx = medianOf(errors);
    step.medianMs = medianOf(ms);
    out.push_back(step);
  }
  progress.finish();
  return out;
}

}  // namespace reftrack::app
