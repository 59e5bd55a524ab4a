#pragma once
// HomographyTrackerParams: registration of each frame to a stored reference frame (paper Sec. 7.3,
// SPEC §5). The guided search window is given at 320x240 and scales with the image.
#include <opencv2/core.hpp>

namespace reftrack {

struct HomographyTrackerParams {
  // Matches are searched within +-this of the predicted position (pixels at 320x240).
  double guidedSearchHalfSizePx = 8.0;
  // Predict with the frame-to-frame homography chained with the last frame-to-reference one
  // (otherwise the last frame-to-reference homography alone is the prediction).
  bool frameToFramePrediction = true;
  // While lost, match every reference corner against the whole frame (else: within the
  // correlation search window around the same position).
  bool reacquireWholeImage = true;

  void check() const;
  void write(cv::FileStorage& fs) const;
  void read(const cv::FileNode& node);
};

}  // namespace reftrack
