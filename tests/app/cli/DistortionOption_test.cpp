#include "app/cli/DistortionOption.hpp"

#include <gtest/gtest.h>

using namespace reftrack::app;

TEST(DistortionOption, ParsesFourOrFiveNumbers) {
  EXPECT_EQ(parseDistortion("-0.3,0,0,0"), (std::vector<double>{-0.3, 0, 0, 0}));
  EXPECT_EQ(parseDistortion("-0.3,0.1,1e-3,-2e-3,0.01"),
            (std::vector<double>{-0.3, 0.1, 1e-3, -2e-3, 0.01}));
  for (const char* bad : {"", "-0.3", "-0.3,0,0", "-0.3,0,0,0,0,0", "a,0,0,0", "-0.3,0,0,0,",
                          "-0.3,,0,0", "-0.3,0,0,nan", "0.1x,0,0,0"})
    EXPECT_FALSE(parseDistortion(bad).has_value()) << bad;
}

// A bad list is a usage error (CLI11 ParseError: exit 2); a good one lands in the target.
TEST(DistortionOption, IsAUsageErrorWhenMalformed) {
  std::vector<double> target;
  CLI::App app;
  addDistortionOption(&app, target);
  app.parse(std::vector<std::string>{"-0.25,0.05,0,0", "--distortion"});
  EXPECT_EQ(target, (std::vector<double>{-0.25, 0.05, 0, 0}));
  CLI::App other;
  addDistortionOption(&other, target);
  EXPECT_THROW(other.parse(std::vector<std::string>{"-0.25,0.05", "--distortion"}),
               CLI::ParseError);
}
