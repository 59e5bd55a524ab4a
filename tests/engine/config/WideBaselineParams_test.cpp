#include "engine/config/WideBaselineParams.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(WideBaselineParams, RoundTrip) {
  WideBaselineParams in;
  in.dx = 7;
  in.dy = 4;
  in.halfWindow = 6;
  in.minScore = 0.5;
  WideBaselineParams out;
  roundTrip(in, out);
  EXPECT_EQ(out.dx, 7);
  EXPECT_EQ(out.dy, 4);
  EXPECT_EQ(out.halfWindow, 6);
  EXPECT_DOUBLE_EQ(out.minScore, 0.5);
}

TEST(WideBaselineParams, EveryBadFieldIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::string, std::function<void(WideBaselineParams&)>>> cases = {
      {"wide_baseline.dx", [](WideBaselineParams& p) { p.dx = -1; }},
      {"wide_baseline.dy", [](WideBaselineParams& p) { p.dy = -1; }},
      {"wide_baseline.n", [](WideBaselineParams& p) { p.halfWindow = 0; }},
      {"wide_baseline.min_score", [&](WideBaselineParams& p) { p.minScore = nan; }},
      {"wide_baseline.affine_neighbours", [](WideBaselineParams& p) { p.affineNeighbours = 2; }},
  };
  for (const auto& [field, mutate] : cases) {
    WideBaselineParams p;
    mutate(p);
    EXPECT_NE(errorMessage([&] { p.check(); }).find(field), std::string::npos) << field;
  }
}
