#pragma once
// WideBaselineParams: matching the current frame to a reference image through the chained
// homography and local affine maps, scored by the warped correlation of Eq. 19 (paper Sec. 6.2).
#include <opencv2/core.hpp>

namespace reftrack {

struct WideBaselineParams {
  int dx = 10;  // candidates within a (2dx+1) x (2dy+1) window around p'_A
  int dy = 10;
  int halfWindow = 5;        // n: the warped correlation compares (2n+1)^2 pixels
  double minScore = 0.7;     // keep the best candidate only above this warped NCC
  int affineNeighbours = 3;  // previous-frame matches defining the local affine map L

  void check() const;
  void write(cv::FileStorage& fs) const;
  void read(const cv::FileNode& node);
};

}  // namespace reftrack
