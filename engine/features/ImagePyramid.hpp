#pragma once
// ImagePyramid: an 8-bit grey image and its cv::pyrDown levels, each level computed on first use
// and kept. One frame's corner detector and homography refiner ask for the same level (at
// 1280x720 both work on 640x360): sharing it saves a whole-frame pyrDown per frame.
#include <deque>
#include <opencv2/core.hpp>

namespace reftrack {

class ImagePyramid {
 public:
  // gray: CV_8UC1, non-empty (else reftrack::Error). The image is shared, not copied.
  explicit ImagePyramid(const cv::Mat& gray);

  // Level 0 is the image; level l + 1 is cv::pyrDown of level l. Throws reftrack::Error when
  // level < 0. Not thread-safe (levels are built lazily); returned references stay valid.
  const cv::Mat& level(int level) const;
  const cv::Mat& image() const { return levels_.front(); }
  // diag(f, f, 1) for f = 2^level: level pixels -> level-0 pixels (cv::pyrDown centres level
  // pixel u on level-0 pixel 2u).
  static cv::Matx33d levelToImage(int level) {
    const double f = static_cast<double>(1 << level);
    return cv::Matx33d(f, 0, 0, 0, f, 0, 0, 0, 1);
  }

 private:
  mutable std::deque<cv::Mat> levels_;  // a deque: references to built levels stay valid
};

}  // namespace reftrack
