#pragma once
// TumSequenceSource: the colour frames of a TUM RGB-D sequence (`--input tum:DIR`): DIR/rgb.txt
// lists `timestamp rgb/FILE.png`; frames carry those timestamps. Depth is not read. Throws
// reftrack::Error naming rgb.txt and the line for a bad layout (see readTumRgbList).
#include <filesystem>

#include "app/sources/StampedImageSource.hpp"

namespace reftrack::app {

class TumSequenceSource final : public StampedImageSource {
 public:
  explicit TumSequenceSource(const std::filesystem::path& dir);
};

}  // namespace reftrack::app
