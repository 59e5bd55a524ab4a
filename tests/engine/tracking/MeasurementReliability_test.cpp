#include "engine/tracking/MeasurementReliability.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace reftrack {
namespace {

// Ten sources, one of which measures twice as badly (SD) as the others: whitened squared
// residuals of 4 against 1.
MeasurementReliability observed(double prior, int rounds) {
  MeasurementReliability r(10, prior);
  for (int k = 0; k < rounds; ++k)
    for (std::size_t s = 0; s < 10; ++s) r.observe(s, s == 0 ? 4.0 : 1.0);
  return r;
}

TEST(MeasurementReliability, EveryFactorIsOneUntilWarmedUpOrWhenOff) {
  MeasurementReliability r(10, 2.0);
  for (int i = 0; i < MeasurementReliability::kWarmUpObservations - 1; ++i) r.observe(0, 100.0);
  EXPECT_EQ(r.varianceFactor(0), 1.0);
  r.observe(1, 1.0);
  EXPECT_GT(r.varianceFactor(0), 1.0);
  EXPECT_EQ(observed(0.0, 100).varianceFactor(0), 1.0);
  EXPECT_EQ(observed(2.0, 100).varianceFactor(10), 1.0);  // out of range
}

// Growing keeps what the sources showed (new sources start unobserved: factor 1, the average);
// shrinking forgets the dropped sources' observations, from the average too.
TEST(MeasurementReliability, ResizingKeepsTheRemainingSourcesObservations) {
  MeasurementReliability r = observed(2.0, 2000);
  const double bad = r.varianceFactor(0);
  r.resize(12);
  EXPECT_EQ(r.sources(), 12u);
  EXPECT_DOUBLE_EQ(r.varianceFactor(0), bad);
  EXPECT_NEAR(r.varianceFactor(11), 1.0, 1e-12);  // prior only: the average itself
  r.resize(1);                                    // only the bad source is left: it is the average
  EXPECT_EQ(r.observations(), 2000);
  EXPECT_NEAR(r.varianceFactor(0), 1.0, 1e-12);
}

// The bad source's variance factor tends to its measured ratio (4 against 1, i.e. 4 / 1.3 and
// 1 / 1.3 of the average 1.3); with two prior observations and 20 of its own it is pulled
// toward the average by 2 / 22 of the way.
TEST(MeasurementReliability, ABadSourceIsWeightedDownByItsMeasuredVariance) {
  const MeasurementReliability many = observed(2.0, 2000);
  EXPECT_NEAR(many.varianceFactor(0), 4.0 / 1.3, 0.01);
  EXPECT_NEAR(many.varianceFactor(5), 1.0 / 1.3, 0.01);
  const MeasurementReliability few = observed(2.0, 20);
  EXPECT_NEAR(few.varianceFactor(0), (2.0 * 1.3 + 80.0) / (22.0 * 1.3), 1e-9);
  EXPECT_LT(few.varianceFactor(0), many.varianceFactor(0));
  EXPECT_GT(few.varianceFactor(5), many.varianceFactor(5));
}

TEST(MeasurementReliability, FactorsAverageAboutOne) {
  const MeasurementReliability r = observed(2.0, 500);
  double sum = 0.0;
  for (std::size_t s = 0; s < 10; ++s) sum += r.varianceFactor(s);
  EXPECT_NEAR(sum / 10.0, 1.0, 0.01);
}

TEST(MeasurementReliability, UnobservedSourcesGetTheAverageAndBadValuesAreIgnored) {
  MeasurementReliability r(11, 2.0);
  for (int k = 0; k < 20; ++k)
    for (std::size_t s = 0; s < 10; ++s) r.observe(s, s == 0 ? 4.0 : 1.0);
  EXPECT_DOUBLE_EQ(r.varianceFactor(10), 1.0);
  const long before = r.observations();
  r.observe(3, std::numeric_limits<double>::quiet_NaN());
  r.observe(3, std::numeric_limits<double>::infinity());
  r.observe(3, -1.0);
  r.observe(99, 1.0);
  EXPECT_EQ(r.observations(), before);
}

}  // namespace
}  // namespace reftrack
