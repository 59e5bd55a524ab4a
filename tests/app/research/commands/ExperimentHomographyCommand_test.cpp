#include <gtest/gtest.h>

#include "TestPaths.hpp"
#include "app/commands/CommandTestSupport.hpp"

using namespace reftrack::test;

TEST(ExperimentHomographyCommand, PrintsTablesAndWritesPlots) {
  const auto dir = freshTempDir("ExperimentHomographyCommand");
  const auto r = runReftrack(
      "experiment-homography --frames 10 --trials 2 --max-angle 20 "
      "--step 10 --out " +
          (dir / "plots").string(),
      dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("10/10"), std::string::npos) << r.out;  // every static frame registered
  EXPECT_NE(r.out.find("pure rotation sweep"), std::string::npos);
  for (const char* png :
       {"static_centre_deviation.png", "rotation_annotation_error.png", "rotation_success.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / "plots" / png)) << png;
  EXPECT_EQ(runReftrack("experiment-homography --experiment nope", dir).exitCode, 2);
  EXPECT_EQ(runReftrack("experiment-homography --step 0", dir).exitCode, 2);
}
