#include "app/research/corners/CornerAccuracyExperiment.hpp"

#include <gtest/gtest.h>

namespace reftrack::app {
namespace {

// Fig. 7's shape: the variance falls with contrast and levels off; the fit follows the measured
// points. 150 trials per step give each variance a relative standard error of ~12%, so the
// monotonic comparison is made between steps 4x apart in amplitude.
TEST(CornerAccuracyExperiment, VarianceFallsWithContrastAndTheFitFollows) {
  CornerAccuracyOptions o;
  o.amplitudes = {20, 60, 160};
  o.trialsPerAmplitude = 150;
  const CornerAccuracyResult r = runCornerAccuracyExperiment(o);
  ASSERT_EQ(r.rows.size(), 3u);
  for (const CornerAccuracyRow& row : r.rows) EXPECT_GT(row.detectionRate, 0.5) << row.amplitude;
  EXPECT_GT(r.rows[0].variancePx2, 2.0 * r.rows[1].variancePx2);
  EXPECT_GT(r.rows[1].variancePx2, r.rows[2].variancePx2);
  // The RMS contrast of a quarter-bright 15x15 window is ~0.43 x amplitude (plus noise).
  EXPECT_NEAR(r.rows[2].rmsContrast, 0.433 * 160, 8.0);
  for (const CornerAccuracyRow& row : r.rows)
    EXPECT_NEAR(r.fitted.variance(row.rmsContrast), row.variancePx2, 0.5 * row.variancePx2);
}

}  // namespace
}  // namespace reftrack::app
