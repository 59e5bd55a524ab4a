#include "engine/features/BlankFrame.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>

namespace reftrack {

bool isBlankFrame(const cv::Mat& frame, double maxStdDev) {
  if (frame.empty()) return true;
  cv::Mat thumbnail;
  // Averages of 8x8-pixel cells (an integer factor: OpenCV's fast area path).
  cv::resize(frame, thumbnail, cv::Size(std::max(1, frame.cols / 8), std::max(1, frame.rows / 8)),
             0, 0, cv::INTER_AREA);
  if (thumbnail.channels() == 3) cv::cvtColor(thumbnail, thumbnail, cv::COLOR_BGR2GRAY);
  cv::Scalar mean, stdDev;
  cv::meanStdDev(thumbnail, mean, stdDev);
  return stdDev[0] < maxStdDev;
}

}  // namespace reftrack
