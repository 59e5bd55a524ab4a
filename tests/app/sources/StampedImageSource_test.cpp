// StampedImageSource: frames keep the listed timestamps, grey becomes BGR, seeking, mean fps,
// clear errors for unreadable or differently sized images.
#include "app/sources/StampedImageSource.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;
namespace fs = std::filesystem;

TEST(StampedImageSource, FramesKeepTheirTimestampsAndGreyBecomesBgr) {
  const fs::path dir = test::freshTempDir("StampedImageSource_ok");
  std::vector<StampedImageFile> list;
  for (int k = 0; k < 3; ++k) {
    const fs::path f = dir / (std::to_string(k) + ".png");
    ASSERT_TRUE(cv::imwrite(f.string(), cv::Mat(6, 8, CV_8UC1, cv::Scalar(10 * (k + 1)))));
    list.push_back({1403636579.76 + 0.05 * k, f});
  }
  StampedImageSource source(list, "fixture");
  EXPECT_EQ(source.frameCount(), 3);
  EXPECT_NEAR(source.fps(), 20.0, 1e-3);  // timestamps near 1.4e9 s resolve 2.4e-7 s
  EXPECT_EQ(source.description(), "fixture (3 frames, 20.0 fps)");
  for (int k = 0; k < 3; ++k) {
    const auto frame = source.next();
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->index, k);
    EXPECT_DOUBLE_EQ(frame->timestamp, list[static_cast<std::size_t>(k)].timestamp);
    EXPECT_EQ(frame->image.type(), CV_8UC3);
    EXPECT_EQ(frame->image.at<cv::Vec3b>(0, 0), cv::Vec3b::all(static_cast<uchar>(10 * (k + 1))));
  }
  EXPECT_FALSE(source.next());
  source.seek(1);
  EXPECT_DOUBLE_EQ(source.next()->timestamp, list[1].timestamp);
  EXPECT_THROW(source.seek(3), Error);
}

TEST(StampedImageSource, BadImagesAreNamed) {
  const fs::path dir = test::freshTempDir("StampedImageSource_bad");
  EXPECT_THROW(StampedImageSource({}, "empty"), Error);
  ASSERT_TRUE(cv::imwrite((dir / "a.png").string(), cv::Mat(6, 8, CV_8UC3)));
  ASSERT_TRUE(cv::imwrite((dir / "b.png").string(), cv::Mat(7, 8, CV_8UC3)));
  std::ofstream(dir / "c.png") << "not an image";
  StampedImageSource source({{0.0, dir / "a.png"}, {0.1, dir / "b.png"}, {0.2, dir / "c.png"}},
                            "fixture");
  EXPECT_TRUE(source.next());
  try {
    source.next();
    FAIL() << "size change not reported";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("b.png' is 8x7 but the first frame of fixture is 8x6"),
              std::string::npos)
        << e.what();
  }
  source.seek(2);
  EXPECT_THROW(source.next(), Error);
}
