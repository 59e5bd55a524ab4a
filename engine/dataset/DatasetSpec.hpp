#pragma once
// DatasetSpec: an input string naming a standard dataset layout, `tum:DIR` (TUM RGB-D: DIR holds
// rgb.txt) or `euroc:DIR` (EuRoC / ASL: DIR is the sequence root holding mav0/, mav0 itself, or
// a camera folder such as mav0/cam0).
#include <filesystem>
#include <optional>
#include <string>

namespace reftrack {

enum class DatasetLayout { Tum, Euroc };

struct DatasetSpec {
  DatasetLayout layout = DatasetLayout::Tum;
  std::filesystem::path dir;
};

// The dataset named by `input`, or nullopt when it starts with neither `tum:` nor `euroc:`.
// Throws reftrack::Error when the prefix is followed by no folder or by one that does not exist.
std::optional<DatasetSpec> parseDatasetSpec(const std::string& input);

}  // namespace reftrack
