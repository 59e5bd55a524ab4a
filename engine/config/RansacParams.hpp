#pragma once
// RansacParams: the paper's robust-homography heuristics (Sec. 7.3, SPEC §5). The sample spacing
// and the inlier threshold are given at 320x240 and scale with the image.
#include <opencv2/core.hpp>

#include "engine/config/ParamSection.hpp"

namespace reftrack {

struct RansacParams : ParamSection<RansacParams> {
  static constexpr const char* kSection = "ransac";

  int maxIterations = 70;             // sampling stops after this many iterations
  double earlyAcceptSupport = 0.75;   // accept at once when support exceeds this fraction
  int earlyAcceptMinIterations = 15;  // ... and at least this many iterations ran
  double minSampleSpacingPx = 60;     // the 4 sampled points pairwise this far apart (320x240)
  double minDeterminant = 0.05;       // reject H unless |det(H / h33)| in [m, 1/m]
  double minInlierRatio = 0.35;       // the frame fails below this inlier fraction
  int minInliers = 8;                 // the frame also fails with fewer inliers than this
  double inlierThresholdPx = 1.0;     // inlier transfer error (pixels at 320x240)
  bool refine = true;                 // non-linear refinement of transfer error on inliers
  int seed = 1;                       // random generator seed (reproducible runs)
  // Draw samples from the best-ranked matches first (PROSAC) when match scores are given; the
  // iteration cap is unchanged. false: uniform sampling as in the paper.
  bool progressiveSampling = true;

  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
};
extern template struct ParamSection<RansacParams>;  // defined in RansacParams.cpp

}  // namespace reftrack
