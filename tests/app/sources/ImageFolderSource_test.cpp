// ImageFolderSource: natural order, globs, seeking, and clear errors for bad images.
#include "app/sources/ImageFolderSource.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;
namespace fs = std::filesystem;

namespace {

// Writes an image whose every pixel holds `value` (so the frame read identifies the file).
void writeImage(const fs::path& file, int value, cv::Size size = {32, 24}) {
  ASSERT_TRUE(cv::imwrite(file.string(), cv::Mat(size, CV_8UC3, cv::Scalar::all(value))));
}

}  // namespace

TEST(ImageFolderSource, NaturalLessComparesDigitRunsByValue) {
  EXPECT_TRUE(naturalLess("img2.png", "img10.png"));
  EXPECT_FALSE(naturalLess("img10.png", "img2.png"));
  EXPECT_TRUE(naturalLess("a.png", "b.png"));
  EXPECT_TRUE(naturalLess("frame_9", "frame_10"));
  EXPECT_TRUE(naturalLess("x01", "x2"));
  EXPECT_FALSE(naturalLess("same", "same"));
}

TEST(ImageFolderSource, ReadsAFolderInNaturalOrderAndSeeks) {
  const fs::path dir = test::freshTempDir("ImageFolderSource_Order");
  writeImage(dir / "img10.png", 30);
  writeImage(dir / "img2.png", 20);
  writeImage(dir / "img1.png", 10);
  std::ofstream(dir / "notes.txt") << "not an image";
  ImageFolderSource source(dir.string(), 20.0);
  ASSERT_EQ(source.frameCount(), 3);
  for (int k = 0; k < 3; ++k) {
    const auto frame = source.next();
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->index, k);
    EXPECT_DOUBLE_EQ(frame->timestamp, k / 20.0);
    EXPECT_EQ(frame->image.at<cv::Vec3b>(0, 0)[0], 10 * (k + 1));
  }
  EXPECT_FALSE(source.next());
  source.seek(1);
  EXPECT_EQ(source.next()->image.at<cv::Vec3b>(0, 0)[0], 20);
  EXPECT_THROW(source.seek(3), Error);
}

TEST(ImageFolderSource, GlobSelectsMatchingFilesOnly) {
  const fs::path dir = test::freshTempDir("ImageFolderSource_Glob");
  writeImage(dir / "a_1.png", 1);
  writeImage(dir / "a_3.png", 3);
  writeImage(dir / "b_2.png", 2);
  ImageFolderSource source((dir / "a_*.png").string());
  ASSERT_EQ(source.frameCount(), 2);
  EXPECT_EQ(source.files()[1].filename(), "a_3.png");
  EXPECT_NE(test::errorMessage([&] {
              ImageFolderSource((dir / "z*.png").string());
            }).find("matches no file"),
            std::string::npos);
}

TEST(ImageFolderSource, UnreadableImageIsNamed) {
  const fs::path dir = test::freshTempDir("ImageFolderSource_Corrupt");
  writeImage(dir / "0.png", 1);
  std::ofstream(dir / "1.png") << "this is no PNG";
  ImageFolderSource source(dir.string());
  ASSERT_TRUE(source.next());
  const std::string message = test::errorMessage([&] { source.next(); });
  EXPECT_NE(message.find((dir / "1.png").string()), std::string::npos) << message;
  EXPECT_NE(message.find("cannot be read"), std::string::npos) << message;
}

TEST(ImageFolderSource, SizeChangeIsNamed) {
  const fs::path dir = test::freshTempDir("ImageFolderSource_Size");
  writeImage(dir / "0.png", 1);
  writeImage(dir / "1.png", 1, {16, 12});
  ImageFolderSource source(dir.string());
  ASSERT_TRUE(source.next());
  const std::string message = test::errorMessage([&] { source.next(); });
  EXPECT_NE(message.find("1.png' is 16x12"), std::string::npos) << message;
  // Photos from several cameras (homography mode): every size is read.
  ImageFolderSource any(dir.string(), 30.0, true);
  ASSERT_TRUE(any.next());
  const std::optional<Frame> second = any.next();
  ASSERT_TRUE(second);
  EXPECT_EQ(second->image.size(), cv::Size(16, 12));
}

TEST(ImageFolderSource, MissingOrEmptyFolderIsAnError) {
  const fs::path dir = test::freshTempDir("ImageFolderSource_Missing");
  EXPECT_NE(test::errorMessage([&] {
              ImageFolderSource((dir / "nope").string());
            }).find("does not exist"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] { ImageFolderSource(dir.string()); }).find("holds no image"),
            std::string::npos);
}
