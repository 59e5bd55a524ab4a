#pragma once
// FrameGrabber: reads a FrameSource on its own thread into a bounded queue. A live source drops
// the oldest queued frame when the queue is full (the viewer always sees recent frames); a file
// source blocks instead, so no frame is ever lost. An exception thrown on the thread is re-thrown
// by next() once the frames before it are consumed. Sources that must be read on the GL thread
// (the simulator) are read synchronously inside next(). A live source that fails (a camera
// unplugged) is reported by disconnected() and reconnected every reconnectInterval until it
// delivers again. The destructor stops the thread.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "app/sources/FrameSource.hpp"

namespace reftrack::app {

class FrameGrabber {
 public:
  explicit FrameGrabber(
      std::unique_ptr<FrameSource> source, std::size_t capacity = 8,
      std::chrono::milliseconds reconnectInterval = std::chrono::milliseconds(500));
  ~FrameGrabber();
  FrameGrabber(const FrameGrabber&) = delete;
  FrameGrabber& operator=(const FrameGrabber&) = delete;

  // The next frame in order (blocking until one is read), nullopt at the end of the source — and
  // for a live source that is disconnected with nothing queued.
  std::optional<Frame> next();
  // True when next() would not block (a frame is queued, the source ended or is disconnected).
  bool frameReady() const;
  // Why a live source delivers nothing now (its error), while it is being reconnected.
  std::optional<std::string> disconnected() const;
  // Empties the queue and continues from frame `index` (seekable sources only).
  void seek(int index);
  const FrameSource& source() const { return *source_; }
  // Frames a live source dropped because the consumer was slower than the camera.
  std::size_t droppedFrames() const;
  std::size_t capacity() const { return capacity_; }

 private:
  void start();
  void stop();
  void run();
  // Live source failed with `why`: reconnects every reconnectInterval_; false when stopping.
  bool waitForReconnection(const std::string& why);

  std::unique_ptr<FrameSource> source_;
  std::size_t capacity_;
  bool threaded_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Frame> queue_;
  bool finished_ = false, stopping_ = false;
  std::exception_ptr error_;
  std::size_t dropped_ = 0;
  std::chrono::milliseconds reconnectInterval_;
  std::optional<std::string> disconnected_;
  std::thread thread_;
};

}  // namespace reftrack::app
