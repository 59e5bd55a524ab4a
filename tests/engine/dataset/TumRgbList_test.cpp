// readTumRgbList: timestamps and files of rgb.txt in order, comments skipped, clear errors.
#include "engine/dataset/TumRgbList.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "DatasetFixtures.hpp"
#include "ErrorMessage.hpp"
#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
namespace fs = std::filesystem;

namespace {

std::string errorOf(const fs::path& dir) {
  return test::errorMessage([&] { readTumRgbList(dir); });
}

}  // namespace

TEST(TumRgbList, ReadsTimestampsAndFilesInOrder) {
  const fs::path dir = test::freshTempDir("TumRgbList_ok");
  const std::vector<double> times = {1305031102.175304, 1305031102.211214, 1305031102.243211};
  std::vector<cv::Mat> images(3, cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(7)));
  test::writeTumSequence(dir, images, times, {});
  const std::vector<StampedImageFile> frames = readTumRgbList(dir);
  ASSERT_EQ(frames.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    // Parsed from the same 6-decimal text the fixture wrote: the nearest double, so exact.
    EXPECT_DOUBLE_EQ(frames[k].timestamp, times[k]);
    EXPECT_TRUE(fs::is_regular_file(frames[k].file)) << frames[k].file;
  }
  EXPECT_EQ(frames[0].file, dir / "rgb" / "1305031102.175304.png");
}

TEST(TumRgbList, BadLayoutsAreClearErrors) {
  const fs::path dir = test::freshTempDir("TumRgbList_bad");
  EXPECT_NE(errorOf(dir).find("has no rgb.txt"), std::string::npos) << errorOf(dir);
  std::vector<cv::Mat> images(2, cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(7)));
  test::writeTumSequence(dir, images, {1.0, 2.0}, {});
  std::ofstream(dir / "rgb.txt") << "# comment\n1.0 rgb/1.000000.png\nnot-a-number rgb/x.png\n";
  EXPECT_NE(errorOf(dir).find("line 3: expected 'timestamp filename'"), std::string::npos)
      << errorOf(dir);
  std::ofstream(dir / "rgb.txt") << "1.0 rgb/1.000000.png\n2.0 rgb/missing.png\n";
  EXPECT_NE(errorOf(dir).find("line 2: image"), std::string::npos) << errorOf(dir);
  EXPECT_NE(errorOf(dir).find("does not exist"), std::string::npos) << errorOf(dir);
  std::ofstream(dir / "rgb.txt") << "2.0 rgb/2.000000.png\n1.0 rgb/1.000000.png\n";
  EXPECT_NE(errorOf(dir).find("does not increase"), std::string::npos) << errorOf(dir);
  std::ofstream(dir / "rgb.txt") << "# only comments\n";
  EXPECT_NE(errorOf(dir).find("lists no frame"), std::string::npos) << errorOf(dir);
}
