// libFuzzer target: parameter YAML — the tracking parameters (`--params` of track/view/extend),
// the preparation parameters (`prepare --params`) and the map-extension file
// (`extend --extend-params`), all from the same bytes.
#include "FuzzInput.hpp"
#include "engine/config/BundleAdjustmentParams.hpp"
#include "engine/config/ConfigValue.hpp"
#include "engine/config/MapExtensionParams.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/reference/ReferencePreparer.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace reftrack;
  const auto file = fuzz::inputFile("params.yml", data, size);
  fuzz::expectOnlyReftrackErrors([&] { TrackerParams::load(file); });
  fuzz::expectOnlyReftrackErrors([&] { ReferencePreparerParams::load(file); });
  fuzz::expectOnlyReftrackErrors([&] {
    MapExtensionParams extension;
    BundleAdjustmentParams bundleAdjustment;
    ReferencePreparerParams preparation;
    readParameterFile(file, [&](const YamlNode& root) {
      extension.read(root["extension"]);
      bundleAdjustment.read(root["bundle_adjustment"]);
      preparation.read(root, {"extension", "bundle_adjustment"});
    });
  });
  return 0;
}
