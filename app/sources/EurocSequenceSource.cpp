#include "app/sources/EurocSequenceSource.hpp"

namespace reftrack::app {

EurocSequenceSource::EurocSequenceSource(const std::filesystem::path& dir)
    : EurocSequenceSource(EurocCamera::open(dir)) {}

EurocSequenceSource::EurocSequenceSource(EurocCamera dataset)
    : StampedImageSource(dataset.frames, "EuRoC '" + dataset.folder.string() + "'"),
      dataset_(std::move(dataset)) {}

}  // namespace reftrack::app
