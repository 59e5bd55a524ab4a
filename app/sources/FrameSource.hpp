#pragma once
// FrameSource: where the viewer's frames come from — a video file, a folder or glob of images, a
// live camera or the simulator. next() returns frames in order (index 0, 1, ...) until the end;
// live sources never end by themselves. Errors (an unreadable frame, a camera that stops) throw
// reftrack::Error naming the source.
#include <opencv2/core.hpp>
#include <optional>
#include <string>

namespace reftrack::app {

struct Frame {
  cv::Mat image;           // CV_8UC3 BGR
  int index = 0;           // position in the source (0-based)
  double timestamp = 0.0;  // seconds since the first frame; the dataset's clock for tum:/euroc:
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // The next frame, or nullopt at the end of a finite source.
  virtual std::optional<Frame> next() = 0;
  // The number of frames when known in advance (files, simulator); nullopt for live sources.
  virtual std::optional<int> frameCount() const = 0;
  // Nominal frame rate (frames per second), used for timestamps and recording.
  virtual double fps() const = 0;
  virtual bool seekable() const { return false; }
  // Makes frame `index` the next one returned; throws reftrack::Error if not seekable or out of
  // range.
  virtual void seek(int index);
  // A live source produces frames in real time and may drop them (cameras).
  virtual bool isLive() const { return false; }
  // Live sources: tries once to reconnect after next() threw (a camera unplugged and plugged in
  // again); true when frames can be read again. Others cannot reconnect.
  virtual bool reconnect() { return false; }
  // True when next() must run on the thread that owns the current GL context (the simulator),
  // so it cannot be read on a grabber thread.
  virtual bool needsGlThread() const { return false; }
  // Human-readable, e.g. "video 'a.mp4' (300 frames, 30 fps)".
  virtual std::string description() const = 0;
};

}  // namespace reftrack::app
