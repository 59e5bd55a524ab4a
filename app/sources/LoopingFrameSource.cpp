#include "app/sources/LoopingFrameSource.hpp"

#include "engine/core/Error.hpp"

namespace reftrack::app {

LoopingFrameSource::LoopingFrameSource(std::unique_ptr<FrameSource> inner, int loops)
    : inner_(std::move(inner)), loops_(loops), count_(0) {
  if (!inner_) throw Error("--loop: no source");
  if (loops < 1) throw Error("--loop must be at least 1");
  if (inner_->isLive() || !inner_->seekable() || !inner_->frameCount())
    throw Error("--loop needs a video file or image folder (" + inner_->description() +
                " cannot be replayed)");
  count_ = *inner_->frameCount();
  if (count_ < 1) throw Error("--loop: " + inner_->description() + " has no frames");
}

std::optional<Frame> LoopingFrameSource::next() {
  for (;;) {
    std::optional<Frame> frame = inner_->next();
    if (frame) {
      const double period = count_ / fps();
      frame->index += loop_ * count_;
      frame->timestamp += loop_ * period;
      return frame;
    }
    if (loop_ + 1 >= loops_) return std::nullopt;
    ++loop_;
    inner_->seek(0);
  }
}

void LoopingFrameSource::seek(int index) {
  if (index < 0 || index >= count_ * loops_)
    throw Error("seek to frame " + std::to_string(index) + " outside 0.." +
                std::to_string(count_ * loops_ - 1) + " of " + description());
  loop_ = index / count_;
  inner_->seek(index % count_);
}

std::string LoopingFrameSource::description() const {
  return inner_->description() + " x" + std::to_string(loops_);
}

}  // namespace reftrack::app
