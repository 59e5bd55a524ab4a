#include "engine/config/CorrelationParams.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(CorrelationParams, RoundTripAndDefaults) {
  CorrelationParams in;
  EXPECT_EQ(in.windowSide(), 11);
  in.halfWindow = 3;
  in.minScore = 0.6;
  in.searchHalfWidthPx = 12;
  in.symmetricCheck = false;
  CorrelationParams out;
  roundTrip(in, out);
  EXPECT_EQ(out.halfWindow, 3);
  EXPECT_DOUBLE_EQ(out.minScore, 0.6);
  EXPECT_DOUBLE_EQ(out.searchHalfWidthPx, 12);
  EXPECT_FALSE(out.symmetricCheck);
}

TEST(CorrelationParams, EveryBadFieldIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::string, std::function<void(CorrelationParams&)>>> cases = {
      {"correlation.half_window", [](CorrelationParams& p) { p.halfWindow = 0; }},
      {"correlation.min_score", [&](CorrelationParams& p) { p.minScore = nan; }},
      {"correlation.search_half_width_px", [](CorrelationParams& p) { p.searchHalfWidthPx = -1; }},
      {"correlation.search_half_height_px",
       [&](CorrelationParams& p) { p.searchHalfHeightPx = nan; }},
  };
  for (const auto& [field, mutate] : cases) {
    CorrelationParams p;
    mutate(p);
    EXPECT_NE(errorMessage([&] { p.check(); }).find(field), std::string::npos) << field;
  }
  auto fs = parseYaml("correlation: { symmetric_check: sometimes }\n");
  CorrelationParams p;
  EXPECT_EQ(errorMessage([&] { p.read(fs["correlation"]); }),
            "line 1: parameter 'correlation.symmetric_check' must be true or false");
}
