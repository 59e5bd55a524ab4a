#include "app/sources/LoopingFrameSource.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "TestPaths.hpp"
#include "app/sources/ImageFolderSource.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {
namespace {

namespace fs = std::filesystem;

fs::path folderOfThree(const std::string& name) {
  const fs::path dir = test::freshTempDir(name);
  for (int i = 0; i < 3; ++i)
    cv::imwrite((dir / cv::format("f%d.png", i)).string(),
                cv::Mat(4, 6, CV_8UC3, cv::Scalar::all(10 * i)));
  return dir;
}

TEST(LoopingFrameSource, ReplaysTheSourceWithIncreasingIndicesAndTimestamps) {
  LoopingFrameSource source(std::make_unique<ImageFolderSource>(folderOfThree("Loop3"), 10.0), 3);
  EXPECT_EQ(source.frameCount(), 9);
  for (int i = 0; i < 9; ++i) {
    const std::optional<Frame> f = source.next();
    ASSERT_TRUE(f) << "frame " << i;
    EXPECT_EQ(f->index, i);
    EXPECT_NEAR(f->timestamp, i / 10.0, 1e-9);
    EXPECT_EQ(f->image.at<cv::Vec3b>(0, 0)[0], 10 * (i % 3));  // the folder's frames, in order
  }
  EXPECT_FALSE(source.next());
  source.seek(4);  // second pass, second frame
  const std::optional<Frame> f = source.next();
  ASSERT_TRUE(f);
  EXPECT_EQ(f->index, 4);
  EXPECT_EQ(f->image.at<cv::Vec3b>(0, 0)[0], 10);
  EXPECT_THROW(source.seek(9), Error);
}

TEST(LoopingFrameSource, RejectsSourcesThatCannotBeReplayed) {
  EXPECT_THROW(
      LoopingFrameSource(std::make_unique<ImageFolderSource>(folderOfThree("Loop0"), 10.0), 0),
      Error);
  EXPECT_THROW(LoopingFrameSource(nullptr, 2), Error);
}

}  // namespace
}  // namespace reftrack::app
