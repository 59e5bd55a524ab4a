#pragma once
// FragmentedMp4Writer: encodes BGR frames (MPEG-4 Part 2 at a constant quantiser, a key frame
// every second) into a fragmented MP4 (one fragment per key frame) with FFmpeg's libraries.
// cv::VideoWriter writes a plain MP4 whose sample index stays in memory until the file is closed
// (about 64 bytes per frame: +1.2 MiB over a 20,000-frame soak); here memory stays flat however
// long the recording, and every write error (a full disk, a file-size limit) is reported.
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>

namespace reftrack::app {

class FragmentedMp4Writer {
 public:
  // Creates `path`. An odd side is padded by one replicated pixel (4:2:0 video needs even
  // sides). Throws reftrack::Error naming the file when the size is empty, fps is not positive,
  // or the encoder or the file cannot be opened.
  FragmentedMp4Writer(const std::filesystem::path& path, double fps, cv::Size size);
  ~FragmentedMp4Writer();  // an unfinished file is closed as it is (its complete fragments play)
  FragmentedMp4Writer(const FragmentedMp4Writer&) = delete;
  FragmentedMp4Writer& operator=(const FragmentedMp4Writer&) = delete;

  // Appends one CV_8UC3 BGR frame of the size given at construction; throws reftrack::Error on
  // a wrong frame or when the encoder or the file refuses it.
  void write(const cv::Mat& bgr);
  // Flushes the encoder and writes the end of the file; throws reftrack::Error on a write error.
  void finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reftrack::app
