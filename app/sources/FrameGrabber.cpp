#include "app/sources/FrameGrabber.hpp"

#include "engine/core/Error.hpp"

namespace reftrack::app {

FrameGrabber::FrameGrabber(std::unique_ptr<FrameSource> source, std::size_t capacity)
    : source_(std::move(source)), capacity_(capacity) {
  if (!source_) throw Error("frame grabber: no source");
  if (capacity_ == 0) throw Error("frame grabber: queue capacity must be at least 1");
  threaded_ = !source_->needsGlThread();
  start();
}

FrameGrabber::~FrameGrabber() { stop(); }

void FrameGrabber::start() {
  if (!threaded_) return;
  {
    std::lock_guard lock(mutex_);
    queue_.clear();
    finished_ = stopping_ = false;
    error_ = nullptr;
  }
  thread_ = std::thread([this] { run(); });
}

void FrameGrabber::stop() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void FrameGrabber::run() {
  const bool live = source_->isLive();
  for (;;) {
    std::optional<Frame> frame;
    try {
      frame = source_->next();
    } catch (...) {
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
      finished_ = true;
      changed_.notify_all();
      return;
    }
    std::unique_lock lock(mutex_);
    if (!frame) {
      finished_ = true;
      changed_.notify_all();
      return;
    }
    if (live) {
      if (queue_.size() >= capacity_) {
        queue_.pop_front();
        ++dropped_;
      }
    } else {
      changed_.wait(lock, [this] { return stopping_ || queue_.size() < capacity_; });
    }
    if (stopping_) return;
    queue_.push_back(std::move(*frame));
    changed_.notify_all();
    if (stopping_) return;
  }
}

std::optional<Frame> FrameGrabber::next() {
  if (!threaded_) return source_->next();
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return !queue_.empty() || finished_; });
  if (!queue_.empty()) {
    Frame frame = std::move(queue_.front());
    queue_.pop_front();
    changed_.notify_all();
    return frame;
  }
  if (error_) std::rethrow_exception(error_);
  return std::nullopt;
}

void FrameGrabber::seek(int index) {
  if (!source_->seekable()) throw Error(source_->description() + " cannot seek");
  stop();
  try {
    source_->seek(index);
  } catch (...) {
    start();  // keep reading from where the source was
    throw;
  }
  start();
}

std::size_t FrameGrabber::droppedFrames() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

}  // namespace reftrack::app
