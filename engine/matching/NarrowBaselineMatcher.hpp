#pragma once
// NarrowBaselineMatcher (paper Sec. 6.1, SPEC §4): for each point of the first set, the
// candidates are the points of the second set inside a search window around its predicted
// position (the same position, or its image under a predicted homography); the best NCC above
// the threshold is kept, and with the symmetric check only mutual best pairs survive.
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "engine/config/CorrelationParams.hpp"
#include "engine/features/Corner.hpp"
#include "engine/matching/CornerMatch.hpp"
#include "engine/matching/NccCorrelation.hpp"

namespace reftrack {

class NarrowBaselineMatcher {
 public:
  explicit NarrowBaselineMatcher(CorrelationParams params = {});  // throws on bad params

  // Points with their windows (same half window). halfWidth/halfHeight in pixels of the second
  // image; firstToSecond predicts where a first point lies in the second image.
  std::vector<CornerMatch> match(const std::vector<cv::Point2f>& first,
                                 const NccPatches& firstPatches,
                                 const std::vector<cv::Point2f>& second,
                                 const NccPatches& secondPatches, double halfWidth,
                                 double halfHeight,
                                 const std::optional<cv::Matx33d>& firstToSecond = {}) const;

  // Unguided matching of two images' corners: square windows, the params' search window
  // scaled to the image size (ResolutionScale.hpp).
  std::vector<CornerMatch> match(const cv::Mat& gray1, const std::vector<Corner>& corners1,
                                 const cv::Mat& gray2, const std::vector<Corner>& corners2) const;

  const CorrelationParams& params() const { return params_; }

 private:
  CorrelationParams params_;
};

}  // namespace reftrack
