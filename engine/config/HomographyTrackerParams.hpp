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
  // While lost, the frame and the reference are matched with this many times the corner count:
  // a frame that barely overlaps the reference (a wide pan) then still shares enough corners
  // with it to be registered. 1: the tracking corner count.
  double reacquireCornerFactor = 3.0;
  // While tracking, each frame is searched with this many times the reference's corner count:
  // two independent selections of the strongest few corners share only part of their corners
  // (measured at 320x240 with 55 on both sides: 31 of 52 visible reference corners matched
  // 2 degrees into a pan), and a denser frame set gives most visible reference corners a
  // counterpart inside the guided search window. 1: the same count on both sides.
  double frameCornerFactor = 2.0;

  void check() const;
  void write(cv::FileStorage& fs) const;
  void read(const cv::FileNode& node);
};

}  // namespace reftrack
