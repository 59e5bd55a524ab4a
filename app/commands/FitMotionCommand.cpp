// `reftrack fit-motion`: the AR(p) motion model and its process noise Q from a recorded
// trajectory (paper Sec. 5.3), written as motion.yml for the tracker and the viewer.
#include <cmath>
#include <cstdio>
#include <memory>

#include "app/commands/Commands.hpp"
#include "engine/core/Error.hpp"
#include "engine/estimation/MotionModelFitter.hpp"

namespace reftrack::app {

namespace {

struct FitMotionOptions {
  std::string trajectory, out;
  int order = 2;
};

void runFitMotion(const FitMotionOptions& o) {
  const TumTrajectory traj = TumTrajectory::load(o.trajectory);
  FittedMotionModel fit = MotionModelFitter::fit(MotionModelFitter::motionVectors(traj), o.order);
  fit.sourceTrajectory = std::filesystem::path(o.trajectory).filename().string();
  saveMotionModel(o.out, fit);

  static const char* names[6] = {"tx", "ty", "tz", "rx", "ry", "rz"};
  std::printf("%s motion model from %d poses of %s (x_k = pose relative to the first camera)\n",
              fit.randomWalk ? "random-walk" : ("AR(" + std::to_string(o.order) + ")").c_str(),
              fit.frameCount, o.trajectory.c_str());
  std::printf("component  explained");
  for (int j = 0; j < fit.model.order(); ++j) std::printf("   w_lag%d", j + 1);
  std::printf("   sd(e) per frame\n");
  for (int c = 0; c < 6; ++c) {
    std::printf("%-9s  %8.1f%%", names[c], 100.0 * fit.explainedVariance[c]);
    for (int j = 0; j < fit.model.order(); ++j) std::printf("  %7.4f", fit.model.weights()[j][c]);
    std::printf("   %.3g %s\n", std::sqrt(fit.model.processNoise()(c, c)), c < 3 ? "m" : "rad");
  }
  std::printf("mean explained variance: %.1f%%\nwrote %s\n", 100.0 * fit.explainedVariance.mean(),
              o.out.c_str());
}

CommandRegistration registerFitMotionCommand(CLI::App& parent) {
  auto options = std::make_shared<FitMotionOptions>();
  CLI::App* sub = parent.add_subcommand(
      "fit-motion", "Fit the AR(p) motion model and its noise Q to a trajectory (paper Sec. 5.3)");
  sub->add_option("--trajectory", options->trajectory, "recorded trajectory (TUM)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--order", options->order, "AR order p (0 = random walk)")
      ->capture_default_str()
      ->check(CLI::Range(0, 20));
  sub->add_option("--out", options->out, "motion model file to write (YAML)")->required();
  return {sub, [options] { runFitMotion(*options); }};
}

const CommandRegistrar registrar(70, registerFitMotionCommand);

}  // namespace

}  // namespace reftrack::app
