#pragma once
// BundleAdjustmentParams (YAML section `bundle_adjustment`): the robust loss, the outlier figure
// of the report and the gauge rule of ReferenceBundleAdjuster. Pixel figures are pixels of the
// map's own images (as the preparation's), not scaled from 320x240.
#include <opencv2/core.hpp>
#include <string>

#include "engine/config/ParamSection.hpp"

namespace reftrack {

struct BundleAdjustmentParams : ParamSection<BundleAdjustmentParams> {
  static constexpr const char* kSection = "bundle_adjustment";

  // Robust loss on each observation's reprojection error (pixels): cauchy | huber | none (plain
  // least squares, for comparison). Both keep the quadratic cost of good (sub-pixel) corners up to
  // lossScalePx; beyond it Cauchy's pull fades away while Huber's stays constant. Measured on the
  // test's synthetic map (0.2 px noise, 10% of the added references' corners 10-40 px off, 2 cm /
  // 1 degree start): Cauchy 1 px 0.10-0.27 mm, 0.011-0.023 degrees, 42 iterations; Huber 1 px
  // 0.21 mm, 0.026 degrees, 100 iterations; least squares 2.0-7.6 mm, 0.23-0.44 degrees.
  std::string loss = "cauchy";
  double lossScalePx = 1.0;
  // Observations whose final reprojection error exceeds this are counted as outliers in the
  // report and left out of its RMS figures (they stay in the map).
  double outlierThresholdPx = 3.0;
  int maxIterations = 100;
  // Gauge: a non-anchored reference is refined only when it sees at least this many points that
  // two already determined references see (anchored ones first, then by closure): a pose has 6
  // unknowns and each point gives 2 equations, so 8 points leave margin for a few outliers.
  // Otherwise its pose (and scale) would float, and it is held where it is.
  int minDeterminedPoints = 8;

  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
};
extern template struct ParamSection<BundleAdjustmentParams>;  // defined in
                                                              // BundleAdjustmentParams.cpp

}  // namespace reftrack
