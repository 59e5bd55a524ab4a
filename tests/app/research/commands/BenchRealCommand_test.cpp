#include <gtest/gtest.h>

#include "TestPaths.hpp"
#include "app/commands/CommandTestSupport.hpp"

using namespace reftrack::test;

// A few frames of the real postcard clip: the command prints both trackers' rows and the ratio.
TEST(BenchRealCommand, PrintsBothTrackersAndTheRatioOnThePostcardClip) {
  const auto data = sharedDataDir();
  const auto clip = data ? *data / "planar-videos" / "video-postcard.mp4" : std::filesystem::path();
  if (!data || !std::filesystem::exists(clip))
    GTEST_SKIP() << "../shared/data/planar-videos/video-postcard.mp4 not available";
  const auto dir = freshTempDir("BenchRealCommand");
  const auto r = runReftrack("bench-real --clip " + clip.string() + " --frames 8 --passes 1", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("card followed in"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("reftrack 6-DOF"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ORB+PnP+Kalman"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("speed ratio baseline / reftrack"), std::string::npos) << r.out;
}

TEST(BenchRealCommand, MissingClipIsAClearErrorAndBadReferencesAUsageError) {
  const auto dir = freshTempDir("BenchRealCommandErrors");
  const auto missing = runReftrack("bench-real --clip " + (dir / "none.mp4").string(), dir);
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_NE(missing.err.find("not found"), std::string::npos) << missing.err;
  EXPECT_NE(missing.err.find("none.mp4"), std::string::npos) << missing.err;
  EXPECT_EQ(runReftrack("bench-real --references 5", dir).exitCode, 2);
  EXPECT_EQ(runReftrack("bench-real --references 5,5", dir).exitCode, 2);
  EXPECT_EQ(runReftrack("bench-real --target 1,2,3", dir).exitCode, 2);
}
