#include "engine/estimation/CornerVarianceModel.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"

namespace reftrack {
namespace {

TEST(CornerVarianceModel, FitRecoversTheGeneratingCurve) {
  const CornerVarianceModel truth{0.01, 4.0, 1.0};  // floor, scale, min contrast
  std::vector<double> c, v;
  for (double contrast = 5; contrast <= 80; contrast += 5) {
    c.push_back(contrast);
    v.push_back(truth.variance(contrast));
  }
  const CornerVarianceModel fit = CornerVarianceModel::fit(c, v);
  EXPECT_NEAR(fit.floorPx2, 0.01, 1e-9);
  EXPECT_NEAR(fit.scalePx2, 4.0, 1e-7);
}

TEST(CornerVarianceModel, FallsWithContrastAndLevelsOff) {
  const CornerVarianceModel m;
  EXPECT_GT(m.variance(5), m.variance(20));
  EXPECT_GT(m.variance(20), m.variance(80));
  EXPECT_NEAR(m.variance(1e6), m.floorPx2, 1e-9);
  EXPECT_TRUE(std::isfinite(m.variance(0)));
  EXPECT_TRUE(std::isfinite(m.variance(std::nan(""))));
}

TEST(CornerVarianceModel, CheckNamesTheBadField) {
  CornerVarianceModel m;
  m.floorPx2 = std::nan("");
  try {
    m.check();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("floor_px2"), std::string::npos);
  }
}

}  // namespace
}  // namespace reftrack
