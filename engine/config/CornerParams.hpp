#pragma once
// CornerParams: Harris corner detection with sub-pixel refinement (paper Sec. 6, SPEC §1, §5).
// Distances and counts are given at 320x240 and scale with the image (ResolutionScale.hpp).
#include <opencv2/core.hpp>

#include "engine/config/ParamSection.hpp"

namespace reftrack {

struct CornerParams : ParamSection<CornerParams> {
  static constexpr const char* kSection = "corners";

  int countAt320x240 = 55;     // paper: 50-60 corners per 320x240 image
  double quality = 0.01;       // minimum Harris response relative to the strongest one
  double minDistancePx = 8.0;  // non-maximum suppression radius at 320x240
  double harrisK = 0.04;       // Harris detector free parameter k
  int blockSize = 5;           // Harris structure-tensor window (pixels, odd)
  int fastThreshold = 20;      // FAST candidate threshold (grey levels); halved when too few
  // Find candidates on the pyramid level nearest 320x240 (positions are refined at full size).
  bool detectAtPaperScale = true;
  int gridColumns = 4;  // corners are spread over a gridColumns x gridRows grid
  int gridRows = 3;
  int subPixelHalfWindow = 3;  // sub-pixel refinement half window (pixels)
  int contrastWindow = 15;     // RMS contrast window around each corner (paper Fig. 7: 15x15)

  // Corner count for an image of this size (countAt320x240 times countScale: ResolutionScale.hpp).
  int countFor(cv::Size imageSize) const;
  double minDistanceFor(cv::Size imageSize) const;

  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
};
extern template struct ParamSection<CornerParams>;  // defined in CornerParams.cpp

}  // namespace reftrack
