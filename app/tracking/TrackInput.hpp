#pragma once
// TrackInput: the frames a `reftrack track` run reads (either mode), with the headless GL context
// that a `sim:` input or a recording needs. At most maxFrames (-1: all). A frame that cannot be
// read, or is not of the expected size, ends the input mid-stream like its end, so every output
// written up to it is kept; the run reports it once the outputs are finished (throwIfCutShort).
// A wrong size on the very first frame throws at once. (anySize: no expected size.)
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "app/sources/FrameSource.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {

class TrackInput {
 public:
  // `input` as `track --input`; frames must be `size` (simulated ones are rendered at it);
  // `sizeOwner` ends the wrong-size message before the size ("the camera is calibrated for").
  TrackInput(const std::string& input, cv::Size size, std::string sizeOwner, int maxFrames,
             bool recording);
  // Frames of any sizes, an image folder's too (photos from several cameras); a `sim:` input is
  // rendered at simSize.
  static TrackInput anySize(const std::string& input, cv::Size simSize, int maxFrames,
                            bool recording);

  // The frames' size: the given one, or (anySize) the last frame's (empty before the first).
  cv::Size frameSize() const { return size_; }

  FrameSource& source() { return *source_; }
  // Frames the run will read, for the progress bar (0 when the source cannot tell).
  int expectedCount() const;
  // The next frame; nullopt at the end of the input, after maxFrames, or at a bad frame.
  std::optional<Frame> next();
  int framesRead() const { return read_; }

  // Throws when no frame was read: the bad first frame's message, or "gave no frames".
  void requireFrames() const;
  // Throws the mid-stream error, if any, naming the last frame the outputs hold.
  void throwIfCutShort() const;

 private:
  TrackInput(const std::string& input, cv::Size size, std::string sizeOwner, int maxFrames,
             bool recording, bool anySize);

  std::string input_, sizeOwner_;
  cv::Size size_;
  bool anySize_ = false;  // no expected size: size_ is the last frame's
  int maxFrames_;
  std::unique_ptr<render::GlContext> gl_;
  std::unique_ptr<FrameSource> source_;
  int read_ = 0, lastIndex_ = -1;
  bool ended_ = false;
  std::string error_;
};

}  // namespace reftrack::app
