#include "app/experiments/SimulatedSequence.hpp"

#include <opencv2/imgproc.hpp>

#include "app/cli/ProgressBar.hpp"
#include "app/simulator/SceneSimulator.hpp"

namespace reftrack::app {

SimulatedSequence simulateSequence(const SimulationOptions& options,
                                   const ReferencePreparerParams& preparation) {
  options.check();
  SimulatedSequence s;
  s.options = options;
  SceneSimulator sim(options);
  s.camera = sim.camera();
  const ReferenceImage a{sim.renderReference('A'), "simulated reference A"};
  const ReferenceImage b{sim.renderReference('B'), "simulated reference B"};
  s.preparation = ReferencePreparer(s.camera, preparation).prepare(a, b, sim.marker());
  ProgressBar progress("render " + options.preset, static_cast<std::size_t>(options.frames));
  for (int k = 0; k < options.frames; ++k) {
    cv::Mat gray;
    cv::cvtColor(sim.renderFrame(k), gray, cv::COLOR_BGR2GRAY);
    s.frames.push_back(gray);
    s.groundTruth.poses.push_back({k / options.fps, sim.framePose(k)});
    progress.advance();
  }
  progress.finish();
  return s;
}

}  // namespace reftrack::app
