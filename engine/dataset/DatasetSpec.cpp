#include "engine/dataset/DatasetSpec.hpp"

#include "engine/core/Error.hpp"

namespace reftrack {

std::optional<DatasetSpec> parseDatasetSpec(const std::string& input) {
  DatasetSpec spec;
  std::string prefix;
  if (input.rfind("tum:", 0) == 0) {
    spec.layout = DatasetLayout::Tum;
    prefix = "tum:";
  } else if (input.rfind("euroc:", 0) == 0) {
    spec.layout = DatasetLayout::Euroc;
    prefix = "euroc:";
  } else {
    return std::nullopt;
  }
  spec.dir = input.substr(prefix.size());
  if (spec.dir.empty())
    throw Error("input '" + input + "': expected " + prefix + "DIR with DIR the dataset folder");
  if (!std::filesystem::is_directory(spec.dir))
    throw Error("input '" + input + "': folder '" + spec.dir.string() + "' does not exist");
  return spec;
}

}  // namespace reftrack
