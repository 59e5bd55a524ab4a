// libFuzzer target: the image size string (`simulate --size`, `view --sim-size`: "640x480").
#include <cstdlib>

#include "FuzzInput.hpp"
#include "app/simulator/SimulationOptions.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto parsed = reftrack::app::parseImageSize(reftrack::fuzz::text(data, size));
  if (parsed && (parsed->width <= 0 || parsed->height <= 0)) std::abort();  // the contract
  return 0;
}
