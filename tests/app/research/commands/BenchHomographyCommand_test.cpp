#include <gtest/gtest.h>

#include "TestPaths.hpp"
#include "app/commands/CommandTestSupport.hpp"

using namespace reftrack::test;

TEST(BenchHomographyCommand, PrintsBothMethodsAndTheRatio) {
  const auto dir = freshTempDir("BenchHomographyCommand");
  const auto r = runReftrack("bench-homography --frames 4 --sizes 320x240", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("reftrack homography"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ORB+BF+findHomography"), std::string::npos);
  EXPECT_NE(r.out.find("speed-up"), std::string::npos);
  EXPECT_EQ(runReftrack("bench-homography --sizes 320", dir).exitCode, 2);
}
