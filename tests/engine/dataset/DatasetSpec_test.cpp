// DatasetSpec: tum:/euroc: prefixes, other inputs untouched, clear errors for missing folders.
#include "engine/dataset/DatasetSpec.hpp"

#include <gtest/gtest.h>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

TEST(DatasetSpec, RecognisesTheTwoLayoutsAndNothingElse) {
  const auto dir = test::freshTempDir("DatasetSpec");
  const auto tum = parseDatasetSpec("tum:" + dir.string());
  ASSERT_TRUE(tum);
  EXPECT_EQ(tum->layout, DatasetLayout::Tum);
  EXPECT_EQ(tum->dir, dir);
  const auto euroc = parseDatasetSpec("euroc:" + dir.string());
  ASSERT_TRUE(euroc);
  EXPECT_EQ(euroc->layout, DatasetLayout::Euroc);
  EXPECT_FALSE(parseDatasetSpec(dir.string()));
  EXPECT_FALSE(parseDatasetSpec("sim:handheld"));
  EXPECT_FALSE(parseDatasetSpec("camera:0"));
}

TEST(DatasetSpec, MissingFolderIsAClearError) {
  try {
    parseDatasetSpec("euroc:/no/such/sequence");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'/no/such/sequence' does not exist"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(parseDatasetSpec("tum:"), Error);
}
