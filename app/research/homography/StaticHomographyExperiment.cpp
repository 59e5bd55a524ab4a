#include "app/research/homography/StaticHomographyExperiment.hpp"

#include <chrono>
#include <cmath>
#include <limits>

#include "app/cli/ProgressBar.hpp"
#include "app/simulator/CameraEffectsPipeline.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "app/simulator/SensorNoise.hpp"
#include "engine/core/Error.hpp"
#include "engine/homography/HomographyDlt.hpp"
#include "engine/homography/HomographyTracker.hpp"

namespace reftrack::app {

void StaticExperimentOptions::check() const {
  if (size.width < 64 || size.height < 48)
    throw Error("static experiment: size must be at least 64x48");
  if (frames < 1) throw Error("static experiment: frames must be at least 1");
  if (!(fovDeg > 1.0 && fovDeg < 170.0))
    throw Error("static experiment: fovDeg must be in (1, 170)");
  if (!(noiseSigma >= 0.0 && noiseSigma <= 100.0))
    throw Error("static experiment: noiseSigma must be in [0, 100]");
  params.check();
  effects.check();
}

SimulationOptions staticViewSimulation(cv::Size size, double fovDeg, std::uint64_t seed,
                                       double noiseSigma, const CameraEffects& effects) {
  SimulationOptions sim;
  sim.preset = "static";
  sim.frames = 1;
  sim.size = size;
  sim.fovDeg = fovDeg;
  sim.seed = seed;
  sim.noiseSigma = noiseSigma;
  sim.effects.photos = effects.photos;
  return sim;
}

StaticExperimentResult runStaticExperiment(const StaticExperimentOptions& options) {
  options.check();
  SceneSimulator simulator(staticViewSimulation(options.size, options.fovDeg, options.seed,
                                                options.noiseSigma, options.effects));
  // One clean render; every frame (and the reference) differs only by its sensor noise.
  const cv::Mat clean = simulator.renderView(simulator.referencePoseA(), 0, 0.0);
  CameraEffectsPipeline camera(
      options.effects,
      CameraSetup{options.size, 30.0, options.frames, options.seed, options.noiseSigma},
      [&](double) { return clean; });
  const cv::Mat reference =
      options.effects.any()
          ? camera.still(clean, mixSeed(options.seed, 0xA11CE))
          : addSensorNoise(clean, mixSeed(options.seed, 0xA11CE), options.noiseSigma);
  HomographyTracker tracker(reference, options.params);
  const cv::Point2d centre((options.size.width - 1) / 2.0, (options.size.height - 1) / 2.0);

  StaticExperimentResult out;
  out.frames = options.frames;
  double sum = 0;
  ProgressBar progress("static", static_cast<std::size_t>(options.frames));
  for (int k = 0; k < options.frames; ++k) {
    const cv::Mat frame =
        options.effects.any()
            ? camera.frame(k)
            : addSensorNoise(clean, mixSeed(options.seed, static_cast<std::uint64_t>(k) + 1),
                             options.noiseSigma);
    const auto t0 = std::chrono::steady_clock::now();
    const HomographyTrackResult r = tracker.track(frame);
    out.milliseconds.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    double deviation = std::numeric_limits<double>::quiet_NaN();
    if (r.tracked) {
      const cv::Point2d q = transferPoint(r.H, centre);
      deviation = std::hypot(q.x - centre.x, q.y - centre.y);
      ++out.registered;
      sum += deviation;
      out.maxDeviationPx = std::max(out.maxDeviationPx, deviation);
    }
    out.centreDeviationPx.push_back(deviation);
    progress.advance();
  }
  progress.finish();
  out.meanDeviationPx = out.registered > 0 ? sum / out.registered : 0.0;
  return out;
}

}  // namespace reftrack::app
