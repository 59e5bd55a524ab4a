// libFuzzer target: labels.yml (AnnotationSet::load, homography mode's `--labels`).
#include "FuzzInput.hpp"
#include "engine/homography/AnnotationSet.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = reftrack::fuzz::inputFile("labels.yml", data, size);
  reftrack::fuzz::expectOnlyReftrackErrors([&] { reftrack::AnnotationSet::load(file); });
  return 0;
}
