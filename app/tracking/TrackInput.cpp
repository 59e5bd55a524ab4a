#include "app/tracking/TrackInput.hpp"

#include <algorithm>
#include <utility>

#include "app/sources/FrameSourceFactory.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

TrackInput::TrackInput(const std::string& input, cv::Size size, std::string sizeOwner,
                       int maxFrames, bool recording)
    : TrackInput(input, size, std::move(sizeOwner), maxFrames, recording, false) {}

TrackInput::TrackInput(const std::string& input, cv::Size size, std::string sizeOwner,
                       int maxFrames, bool recording, bool anySize)
    : input_(input),
      sizeOwner_(std::move(sizeOwner)),
      size_(size),
      anySize_(anySize),
      maxFrames_(maxFrames) {
  if (isSimulatorInput(input) || recording) gl_ = render::createHeadlessContext();
  FrameSourceOptions options;
  options.simSize = size;
  options.anyImageSizes = anySize;
  source_ = openFrameSource(input, options);
  if (anySize) size_ = cv::Size();
}

TrackInput TrackInput::anySize(const std::string& input, cv::Size simSize, int maxFrames,
                               bool recording) {
  return TrackInput(input, simSize, "", maxFrames, recording, true);
}

int TrackInput::expectedCount() const {
  const int count = maxFrames_ > 0
                        ? std::min(maxFrames_, source_->frameCount().value_or(maxFrames_))
                        : source_->frameCount().value_or(0);
  return std::max(count, 0);
}

std::optional<Frame> TrackInput::next() {
  if (ended_ || (maxFrames_ >= 0 && read_ >= maxFrames_)) return std::nullopt;
  std::optional<Frame> frame;
  try {
    frame = source_->next();
  } catch (const Error& e) {
    error_ = e.what();
  }
  if (frame && anySize_) size_ = frame->image.size();
  if (frame && frame->image.size() != size_) {
    error_ = "input '" + input_ + "' frame " + std::to_string(frame->index) + " is " +
             std::to_string(frame->image.cols) + "x" + std::to_string(frame->image.rows) + " but " +
             sizeOwner_ + " " + std::to_string(size_.width) + "x" + std::to_string(size_.height);
    if (read_ == 0) throw Error(error_);
    frame.reset();
  }
  if (!frame) {
    ended_ = true;
    return std::nullopt;
  }
  ++read_;
  lastIndex_ = frame->index;
  return frame;
}

void TrackInput::requireFrames() const {
  if (read_ == 0) throw Error(error_.empty() ? "input '" + input_ + "' gave no frames" : error_);
}

void TrackInput::throwIfCutShort() const {
  if (!error_.empty())
    throw Error(error_ + " (outputs written up to frame " + std::to_string(lastIndex_) + ")");
}

}  // namespace reftrack::app
