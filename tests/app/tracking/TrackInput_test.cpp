#include "app/tracking/TrackInput.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

// A folder of PNG frames 000000.png ... of the given sizes.
std::string writeFrames(const std::string& name, const std::vector<cv::Size>& sizes) {
  const auto dir = test::freshTempDir(name);
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    char file[32];
    std::snprintf(file, sizeof file, "%06zu.png", k);
    cv::imwrite((dir / file).string(), cv::Mat(sizes[k], CV_8UC3, cv::Scalar::all(40 + 10 * k)));
  }
  return dir.string();
}

}  // namespace

TEST(TrackInput, ReadsEveryFrameUpToMaxFrames) {
  const std::string dir = writeFrames("TrackInput_all", {{32, 24}, {32, 24}, {32, 24}});
  TrackInput all(dir, {32, 24}, "the camera is calibrated for", -1, false);
  EXPECT_EQ(all.expectedCount(), 3);
  int n = 0;
  while (const auto frame = all.next()) EXPECT_EQ(frame->index, n++);
  EXPECT_EQ(all.framesRead(), 3);
  EXPECT_NO_THROW(all.requireFrames());
  EXPECT_NO_THROW(all.throwIfCutShort());
  EXPECT_FALSE(all.next());  // stays ended

  TrackInput two(dir, {32, 24}, "the camera is calibrated for", 2, false);
  EXPECT_EQ(two.expectedCount(), 2);
  while (two.next()) {
  }
  EXPECT_EQ(two.framesRead(), 2);
}

// A frame the source cannot deliver mid-stream (here: an image folder whose third image changes
// size) ends the input; the run learns why once its outputs are written.
TEST(TrackInput, AFailureMidStreamEndsTheInputAndIsReportedAfterwards) {
  const std::string dir = writeFrames("TrackInput_mid", {{32, 24}, {32, 24}, {40, 30}, {32, 24}});
  TrackInput input(dir, {32, 24}, "the camera is calibrated for", -1, false);
  while (input.next()) {
  }
  EXPECT_EQ(input.framesRead(), 2);
  EXPECT_NO_THROW(input.requireFrames());
  const std::string message = test::errorMessage([&] { input.throwIfCutShort(); });
  EXPECT_NE(message.find("000002.png' is 40x30"), std::string::npos) << message;
  EXPECT_NE(message.find("(outputs written up to frame 1)"), std::string::npos) << message;
}

// On the first frame a wrong size is an error at once: nothing would be written.
TEST(TrackInput, AWrongSizedFirstFrameThrows) {
  const std::string dir = writeFrames("TrackInput_first", {{40, 30}, {32, 24}});
  TrackInput input(dir, {32, 24}, "the reference 'ref.png' is", -1, false);
  EXPECT_EQ(test::errorMessage([&] { input.next(); }),
            "input '" + dir + "' frame 0 is 40x30 but the reference 'ref.png' is 32x24");
  EXPECT_EQ(input.framesRead(), 0);
  EXPECT_NE(test::errorMessage([&] { input.requireFrames(); }).find("frame 0 is 40x30"),
            std::string::npos);
}

// Homography mode without a camera: frames of any sizes, an image folder's too (photos from
// several cameras); frameSize() follows them.
TEST(TrackInput, AnySizeReadsFramesOfEverySize) {
  const std::string dir = writeFrames("TrackInput_any", {{40, 30}, {40, 30}, {32, 24}});
  TrackInput input = TrackInput::anySize(dir, {64, 48}, -1, false);
  EXPECT_EQ(input.frameSize(), cv::Size());
  ASSERT_TRUE(input.next().has_value());
  EXPECT_EQ(input.frameSize(), cv::Size(40, 30));
  ASSERT_TRUE(input.next().has_value());
  const std::optional<Frame> third = input.next();
  ASSERT_TRUE(third.has_value());
  EXPECT_EQ(third->image.size(), cv::Size(32, 24));
  EXPECT_EQ(input.frameSize(), cv::Size(32, 24));
  EXPECT_FALSE(input.next().has_value());
  EXPECT_EQ(input.framesRead(), 3);
  EXPECT_NO_THROW(input.throwIfCutShort());
}
