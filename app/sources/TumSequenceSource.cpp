#include "app/sources/TumSequenceSource.hpp"

#include "engine/dataset/TumRgbList.hpp"

namespace reftrack::app {

TumSequenceSource::TumSequenceSource(const std::filesystem::path& dir)
    : StampedImageSource(readTumRgbList(dir), "TUM RGB-D '" + dir.string() + "'") {}

}  // namespace reftrack::app
