// libFuzzer target: camera.yml (PinholeCamera::load).
#include "FuzzInput.hpp"
#include "engine/geometry/PinholeCamera.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = reftrack::fuzz::inputFile("camera.yml", data, size);
  reftrack::fuzz::expectOnlyReftrackErrors([&] { reftrack::PinholeCamera::load(file); });
  return 0;
}
