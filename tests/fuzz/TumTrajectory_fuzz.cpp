// libFuzzer target: TUM trajectories (TumTrajectory::load: `--poses`, `eval --gt/--est`,
// `fit-motion --trajectory`).
#include "FuzzInput.hpp"
#include "engine/geometry/TumTrajectory.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = reftrack::fuzz::inputFile("trajectory.txt", data, size);
  reftrack::fuzz::expectOnlyReftrackErrors([&] { reftrack::TumTrajectory::load(file); });
  return 0;
}
