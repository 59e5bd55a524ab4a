// VideoFileSource: reads every frame of an MP4 in order, seeks, and names a missing file.
#include "app/sources/VideoFileSource.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/videoio.hpp>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;
namespace fs = std::filesystem;

namespace {

// 12 frames at 15 fps; frame k is uniformly grey 20 k (so decoded frames identify themselves
// within codec error).
fs::path writeVideo(const fs::path& dir) {
  const fs::path file = dir / "clip.mp4";
  cv::VideoWriter writer(file.string(), cv::CAP_FFMPEG, cv::VideoWriter::fourcc('m', 'p', '4', 'v'),
                         15.0, {64, 48});
  EXPECT_TRUE(writer.isOpened());
  for (int k = 0; k < 12; ++k) writer.write(cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(20 * k)));
  writer.release();
  return file;
}

}  // namespace

TEST(VideoFileSource, ReadsAllFramesInOrderAtTheFileRate) {
  const fs::path dir = test::freshTempDir("VideoFileSource_Read");
  VideoFileSource source(writeVideo(dir));
  EXPECT_DOUBLE_EQ(source.fps(), 15.0);
  EXPECT_EQ(source.frameCount(), 12);
  int n = 0;
  while (const auto frame = source.next()) {
    EXPECT_EQ(frame->index, n);
    EXPECT_NEAR(frame->timestamp, n / 15.0, 1e-9);
    EXPECT_EQ(frame->image.size(), cv::Size(64, 48));
    // Flat grey survives MPEG-4 coding within a few levels.
    EXPECT_NEAR(cv::mean(frame->image)[1], 20.0 * n, 4.0) << "frame " << n;
    ++n;
  }
  EXPECT_EQ(n, 12);
  source.seek(5);
  const auto fifth = source.next();
  ASSERT_TRUE(fifth);
  EXPECT_EQ(fifth->index, 5);
  EXPECT_NEAR(cv::mean(fifth->image)[1], 100.0, 4.0);
}

TEST(VideoFileSource, MissingOrCorruptFileIsNamed) {
  const fs::path dir = test::freshTempDir("VideoFileSource_Bad");
  try {
    VideoFileSource source(dir / "missing.mp4");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.mp4' does not exist"), std::string::npos);
  }
  std::ofstream(dir / "junk.mp4") << "not a video at all";
  try {
    VideoFileSource source(dir / "junk.mp4");
    source.next();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("junk.mp4'"), std::string::npos) << e.what();
  }
}
