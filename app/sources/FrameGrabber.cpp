#include "app/sources/FrameGrabber.hpp"

#include "engine/core/Error.hpp"

namespace reftrack::app {

FrameGrabber::FrameGrabber(std::unique_ptr<FrameSource> source, std::size_t capacity,
                           std::chrono::milliseconds reconnectInterval)
    : source_(std::move(source)), capacity_(capacity), reconnectInterval_(reconnectInterval) {
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
    disconnected_.reset();
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
    } catch (const std::exception& e) {
      if (live) {
        if (!waitForReconnection(e.what())) return;  // stopping
        continue;
      }
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
      finished_ = true;
      changed_.notify_all();
      return;
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

bool FrameGrabber::waitForReconnection(const std::string& why) {
  std::unique_lock lock(mutex_);
  disconnected_ = why;
  changed_.notify_all();
  for (;;) {
    if (changed_.wait_for(lock, reconnectInterval_, [this] { return stopping_; })) return false;
    lock.unlock();
    const bool back = source_->reconnect();
    lock.lock();
    if (back) {
      disconnected_.reset();
      changed_.notify_all();
      return true;
    }
  }
}

bool FrameGrabber::frameReady() const {
  if (!threaded_) return true;
  std::lock_guard lock(mutex_);
  return !queue_.empty() || finished_ || disconnected_.has_value();
}

std::optional<std::string> FrameGrabber::disconnected() const {
  std::lock_guard lock(mutex_);
  return disconnected_;
}

std::optional<Frame> FrameGrabber::next() {
  if (!threaded_) return source_->next();
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return !queue_.empty() || finished_ || disconnected_; });
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
