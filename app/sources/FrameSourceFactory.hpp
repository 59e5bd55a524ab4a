#pragma once
// openFrameSource: the source named by a `--input` string:
//   camera:N          live camera N
//   sim:PRESET        the simulator on the fly (needs a current GL context on this thread)
//   tum:DIR           a TUM RGB-D sequence (DIR/rgb.txt), frames with its timestamps
//   euroc:DIR         a EuRoC / ASL sequence's cam0 (DIR, DIR/mav0 or the camera folder),
//                     frames with its timestamps
//   a folder          its images, natural order
//   a glob pattern    e.g. "frames/*.png"
//   any other path    a video file
// Throws reftrack::Error naming the input when it does not exist or cannot be opened.
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "app/sources/FrameSource.hpp"

namespace reftrack::app {

struct FrameSourceOptions {
  double imageFps = 30.0;  // nominal rate of image folders (and the simulator)
  int simFrames = 300;     // simulator sequence length
  cv::Size simSize{640, 480};
  std::uint64_t simSeed = 1;
  bool anyImageSizes = false;  // image folders may hold images of several sizes
};

std::unique_ptr<FrameSource> openFrameSource(const std::string& input,
                                             const FrameSourceOptions& options = {});

// True when `input` is `sim:...` (the caller then needs a GL context before opening it).
bool isSimulatorInput(const std::string& input);

}  // namespace reftrack::app
