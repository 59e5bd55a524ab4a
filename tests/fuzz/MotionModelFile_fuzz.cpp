// libFuzzer target: motion.yml (loadMotionModel, `pose.motion_model_file`).
#include "FuzzInput.hpp"
#include "engine/estimation/MotionModelFile.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = reftrack::fuzz::inputFile("motion.yml", data, size);
  reftrack::fuzz::expectOnlyReftrackErrors([&] { reftrack::loadMotionModel(file); });
  return 0;
}
