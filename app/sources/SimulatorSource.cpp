#include "app/sources/SimulatorSource.hpp"

#include "engine/core/Error.hpp"

namespace reftrack::app {

SimulatorSource::SimulatorSource(const SimulationOptions& options) {
  options.check();
  sim_ = std::make_unique<SceneSimulator>(options);
}

std::optional<Frame> SimulatorSource::next() {
  if (nextIndex_ >= sim_->options().frames) return std::nullopt;
  Frame frame{sim_->renderFrame(nextIndex_), nextIndex_, nextIndex_ / sim_->options().fps};
  ++nextIndex_;
  return frame;
}

void SimulatorSource::seek(int index) {
  if (index < 0 || index >= sim_->options().frames)
    throw Error(description() + ": frame " + std::to_string(index) + " is out of range");
  nextIndex_ = index;
}

std::string SimulatorSource::description() const {
  const SimulationOptions& o = sim_->options();
  return "simulator '" + o.preset + "' (" + std::to_string(o.frames) + " frames, " +
         std::to_string(o.size.width) + "x" + std::to_string(o.size.height) + ")";
}

TumTrajectory SimulatorSource::groundTruth() const {
  TumTrajectory t;
  const SimulationOptions& o = sim_->options();
  for (int k = 0; k < o.frames; ++k) t.poses.push_back({k / o.fps, sim_->framePose(k)});
  return t;
}

}  // namespace reftrack::app
