#include "engine/reference/MarkerSpec.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"

using namespace reftrack;

TEST(MarkerSpec, ParsesDictIdSide) {
  const MarkerSpec m = MarkerSpec::parse("DICT_4X4_50:3:0.08");
  EXPECT_EQ(m.dictionary, "DICT_4X4_50");
  EXPECT_EQ(m.id, 3);
  EXPECT_DOUBLE_EQ(m.sideMetres, 0.08);
  EXPECT_EQ(MarkerSpec::parse(m.toString()).id, 3);
  const auto c = m.cornersWorld();
  EXPECT_DOUBLE_EQ(c[0].x(), -0.04);
  EXPECT_DOUBLE_EQ(c[0].y(), 0.04);
  EXPECT_DOUBLE_EQ(c[2].y(), -0.04);
}

TEST(MarkerSpec, RejectsMalformedText) {
  for (const char* bad : {"DICT_6X6_250:23", "DICT_6X6_250:x:0.1", "DICT_6X6_250:23:-1",
                          "DICT_6X6_250:300:0.1", "DICT_9X9:1:0.1", "DICT_6X6_250:1:0.1abc"})
    EXPECT_THROW(MarkerSpec::parse(bad), Error) << bad;
}
