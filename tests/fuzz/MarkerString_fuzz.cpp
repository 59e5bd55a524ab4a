// libFuzzer target: the marker string (`prepare --marker DICT:ID:SIDE_M`).
#include "FuzzInput.hpp"
#include "engine/reference/MarkerSpec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  reftrack::fuzz::expectOnlyReftrackErrors([&] {
    const reftrack::MarkerSpec marker =
        reftrack::MarkerSpec::parse(reftrack::fuzz::text(data, size));
    (void)reftrack::MarkerSpec::parse(marker.toString());
  });
  return 0;
}
