#include "app/sources/FrameSource.hpp"

#include "engine/core/Error.hpp"

namespace reftrack::app {

void FrameSource::seek(int index) {
  throw Error(description() + " cannot seek (asked for frame " + std::to_string(index) + ")");
}

}  // namespace reftrack::app
