#pragma once
// The paper's Fig. 7 experiment with this project's CornerDetector: an ideal square corner at a
// random sub-pixel position (exact area-coverage anti-aliasing), Gaussian noise of SD 5 grey
// levels, a sweep of step amplitudes; per amplitude the measured RMS contrast of the 15x15 window,
// the detection rate and the variance of the detected position. The fitted curve is the corner
// variance model the 6-DOF tracker weights its residuals with.
#include <cstdint>
#include <vector>

#include "engine/config/CornerParams.hpp"
#include "engine/estimation/CornerVarianceModel.hpp"

namespace reftrack::app {

struct CornerAccuracyOptions {
  std::vector<double> amplitudes{6, 8, 10, 12, 16, 20, 25, 30, 40, 50, 60, 80, 100, 130, 160, 200};
  int trialsPerAmplitude = 300;
  double noiseSigma = 5.0;
  std::uint64_t seed = 1;
  CornerParams corners;
};

struct CornerAccuracyRow {
  double amplitude = 0;
  double rmsContrast = 0;    // mean over trials (grey levels)
  double detectionRate = 0;  // fraction of trials with a corner within 2 px of the truth
  double variancePx2 = 0;    // mean of the x and y position variances (px^2)
  double biasPx = 0;         // length of the mean error vector (px)
};

struct CornerAccuracyResult {
  std::vector<CornerAccuracyRow> rows;
  CornerVarianceModel fitted;
};

CornerAccuracyResult runCornerAccuracyExperiment(const CornerAccuracyOptions& options);

}  // namespace reftrack::app
