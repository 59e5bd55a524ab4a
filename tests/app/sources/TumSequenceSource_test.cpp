// TumSequenceSource: the rgb.txt frames, in order, with their timestamps; bad layouts named.
#include "app/sources/TumSequenceSource.hpp"

#include <gtest/gtest.h>

#include "DatasetFixtures.hpp"
#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(TumSequenceSource, ReadsFramesWithTheirTimestamps) {
  const auto dir = test::freshTempDir("TumSequenceSource_ok");
  std::vector<cv::Mat> images;
  std::vector<double> times;
  for (int k = 0; k < 4; ++k) {
    images.emplace_back(12, 16, CV_8UC3, cv::Scalar(k * 20, 0, 0));
    times.push_back(1305031102.175304 + k * 0.033);
  }
  test::writeTumSequence(dir, images, times, {});
  TumSequenceSource source(dir);
  ASSERT_EQ(source.frameCount(), 4);
  EXPECT_NEAR(source.fps(), 1.0 / 0.033, 1e-3);
  EXPECT_NE(source.description().find("TUM RGB-D"), std::string::npos);
  for (int k = 0; k < 4; ++k) {
    const auto frame = source.next();
    ASSERT_TRUE(frame);
    EXPECT_DOUBLE_EQ(frame->timestamp, times[static_cast<std::size_t>(k)]);
    EXPECT_EQ(frame->image.at<cv::Vec3b>(5, 5)[0], k * 20);
  }
  EXPECT_FALSE(source.next());
}

TEST(TumSequenceSource, FolderWithoutRgbTxtIsAClearError) {
  const auto dir = test::freshTempDir("TumSequenceSource_bad");
  try {
    TumSequenceSource source(dir);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("has no rgb.txt"), std::string::npos) << e.what();
  }
}
