#pragma once
// FrameGrabber: reads a FrameSource on its own thread into a bounded queue. A live source drops
// the oldest queued frame when the queue is full (the viewer always sees recent frames); a file
// source blocks instead, so no frame is ever lost. An exception thrown on the thread is re-thrown
// by next() once the frames before it are consumed. Sources that must be read on the GL thread
// (the simulator) are read synchronously inside next(). The destructor stops the thread.
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include "app/sources/FrameSource.hpp"

namespace reftrack::app {

class FrameGrabber {
 public:
  explicit FrameGrabber(std::unique_ptr<FrameSource> source, std::size_t capacity = 8);
  ~FrameGrabber();
  FrameGrabber(const FrameGrabber&) = delete;
  FrameGrabber& operator=(const FrameGrabber&) = delete;

  // The next frame in order (blocking until one is read), nullopt at the end of the source.
  std::optional<Frame> next();
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

  std::unique_ptr<FrameSource> source_;
  std::size_t capacity_;
  bool threaded_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Frame> queue_;
  bool finished_ = false, stopping_ = false;
  std::exception_ptr error_;
  std::size_t dropped_ = 0;
  std::thread thread_;
};

}  // namespace reftrack::app
