#include "engine/core/TemporaryOutputs.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "TestPaths.hpp"

namespace reftrack {
namespace {

namespace fs = std::filesystem;

TEST(TemporaryOutputs, RemovesExactlyTheTrackedFilesThatAreStillAlive) {
  const fs::path dir = test::freshTempDir("TemporaryOutputs");
  const fs::path a = dir / "a.tmp", b = dir / "b.tmp", kept = dir / "kept.txt";
  for (const fs::path& p : {a, b, kept}) std::ofstream(p) << "x";
  {
    const TemporaryOutput finished(b);  // goes out of scope: no longer tracked
  }
  const TemporaryOutput tracked(a);
  EXPECT_GE(removeTemporaryOutputs(), 1);
  EXPECT_FALSE(fs::exists(a));
  EXPECT_TRUE(fs::exists(b));
  EXPECT_TRUE(fs::exists(kept));
}

}  // namespace
}  // namespace reftrack
