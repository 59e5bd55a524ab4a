#pragma once
// CornerVarianceModel (paper Fig. 7, SPEC §3): the variance of a detected corner's position as a
// function of the RMS contrast c of the 15x15 window around it, var(c) = floor + scale / c^2
// (px^2). It falls with contrast and levels off at `floor`. The defaults are this project's fit of
// the Fig. 7 experiment (`reftrack corner-variance`: 300 trials per step, seed 1) with its own
// CornerDetector: 0.0030 + 13.2 / c^2.
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack {

struct CornerVarianceModel {
  double floorPx2 = 0.0030;  // variance at high contrast (px^2)
  double scalePx2 = 13.2;    // grows as scale / contrast^2 at low contrast (px^2 grey^2)
  double minContrast = 2.0;  // contrast is clamped below this to keep weights finite

  double variance(double rmsContrast) const;
  double sigma(double rmsContrast) const;
  void check() const;  // throws reftrack::Error naming the bad field

  // Least-squares fit of floor and scale to measured (contrast, variance) pairs (>= 2 pairs).
  static CornerVarianceModel fit(const std::vector<double>& contrast,
                                 const std::vector<double>& variance);
};

}  // namespace reftrack
