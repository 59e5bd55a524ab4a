#pragma once
// SimulatorSource: frames of the synthetic desk scene rendered on demand (`sim:PRESET`), with
// the simulator's exact camera and ground-truth poses. Rendering uses the GL context current on
// the calling thread, so it must be constructed and read on the thread owning that context
// (needsGlThread() is true; FrameGrabber then reads it synchronously).
#include <memory>

#include "app/simulator/SceneSimulator.hpp"
#include "app/sources/FrameSource.hpp"
#include "engine/geometry/TumTrajectory.hpp"

namespace reftrack::app {

class SimulatorSource final : public FrameSource {
 public:
  // Throws reftrack::Error for bad options (SimulationOptions::check) or without a context.
  explicit SimulatorSource(const SimulationOptions& options);

  std::optional<Frame> next() override;
  std::optional<int> frameCount() const override { return sim_->options().frames; }
  double fps() const override { return sim_->options().fps; }
  bool seekable() const override { return true; }
  void seek(int index) override;
  bool needsGlThread() const override { return true; }
  std::string description() const override;

  const PinholeCamera& camera() const { return sim_->camera(); }
  // Ground truth world->camera of every frame, timestamped like the frames.
  TumTrajectory groundTruth() const;

 private:
  std::unique_ptr<SceneSimulator> sim_;
  int nextIndex_ = 0;
};

}  // namespace reftrack::app
