#pragma once
// CornerDetector: Harris-type corners with sub-pixel refinement, spread over the image (paper
// Sec. 6, SPEC §1, §5). FAST proposes candidates (on the pyramid level nearest 320x240 unless
// disabled), each is scored with the Harris measure, the strongest are kept under a per-cell
// quota on a grid and a minimum spacing, refined to sub-pixel accuracy (SubPixelCorner.hpp, on
// the pyramid level, then at full resolution) and given the RMS contrast of the window around
// them.
#include <opencv2/core.hpp>
#include <vector>

#include "engine/config/CornerParams.hpp"
#include "engine/features/Corner.hpp"
#include "engine/features/ImagePyramid.hpp"

namespace reftrack {

class CornerDetector {
 public:
  explicit CornerDetector(CornerParams params = {});  // throws reftrack::Error on bad params

  // gray: CV_8UC1 (a 3-channel BGR image is converted). At most params.countFor(size) corners,
  // strongest first. Throws reftrack::Error on an empty image or an unsupported type. The FAST
  // threshold adapts to the image and to the corners delivered, and is remembered for the next call
  // (so one detector must not be used from two threads at once).
  std::vector<Corner> detect(const cv::Mat& image) const;
  // The same on an 8-bit grey image's pyramid, whose level the detection works on is then built
  // once for every user of the pyramid (the homography refiner aligns on the same level).
  std::vector<Corner> detect(const ImagePyramid& pyramid) const;

  const CornerParams& params() const { return params_; }

 private:
  CornerParams params_;
  mutable int thresholdHint_ = 0;  // FAST threshold of the last call (0: none yet)
  mutable int producedHint_ = 0;   // decaying maximum of the corners delivered (0: none yet)
};

// The 8-bit single-channel view of an image (converted from BGR/BGRA/16-bit when needed).
// Throws reftrack::Error naming the type on anything else.
cv::Mat toGray8(const cv::Mat& image);

}  // namespace reftrack
