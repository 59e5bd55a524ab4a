#pragma once
// CalibrationInput: the images `reftrack calibrate` reads. SRC is a folder (its image files,
// sorted by name), a glob pattern with * or ? such as "shots/*.png" (cv::glob), one image file, or
// a video file; a long video is sampled evenly so that at most maxVideoFrames frames are examined.
#include <cstddef>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

namespace reftrack {

class CalibrationInput {
 public:
  // Throws reftrack::Error when SRC names nothing readable (no images, video cannot be opened).
  explicit CalibrationInput(const std::string& source, int maxVideoFrames = 300);

  bool isVideo() const { return video_ != nullptr; }
  // How many images next() will deliver (for a video: an estimate from its frame count).
  std::size_t size() const { return size_; }
  // The next image and a label naming it (file name or "frame N"); false at the end.
  // Throws reftrack::Error when an image file cannot be decoded.
  bool next(cv::Mat& image, std::string& label);

 private:
  std::vector<std::string> files_;
  std::size_t nextFile_ = 0;
  std::unique_ptr<cv::VideoCapture> video_;
  long long videoFrame_ = 0;
  int videoStep_ = 1;
  std::size_t size_ = 0;
};

}  // namespace reftrack
