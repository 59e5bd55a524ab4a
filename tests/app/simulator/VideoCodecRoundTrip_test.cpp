#include "app/simulator/VideoCodecRoundTrip.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

// 30 frames of the bundled photograph (a real image) panning 0.7 px per frame, 640x480.
std::vector<cv::Mat> panningPhoto() {
  const cv::Mat photo =
      cv::imread((test::sourceDir() / "assets/textures/cookie-box.jpg").string(), cv::IMREAD_COLOR);
  EXPECT_FALSE(photo.empty());
  cv::Mat big;
  cv::resize(photo, big, {720, 520}, 0, 0, cv::INTER_CUBIC);
  std::vector<cv::Mat> frames;
  for (int k = 0; k < 30; ++k) {
    const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -0.7 * k, 0, 1, -0.3 * k);
    cv::Mat frame;
    cv::warpAffine(big, frame, shift, {640, 480});
    frames.push_back(frame);
  }
  return frames;
}

double rawBytes(const std::vector<cv::Mat>& frames) {
  return static_cast<double>(frames.size() * frames.front().total() * 3);
}

}  // namespace

TEST(VideoCodecRoundTrip, H264CompressesAtAWebcamBitrateAndKeepsTheImage) {
  const std::vector<cv::Mat> frames = panningPhoto();
  const EncodedVideo video = roundTripVideo(frames, "h264", 30.0);
  ASSERT_EQ(video.frames.size(), frames.size());
  // A webcam stream at 640x480 / 30 fps carries ~0.3-3 Mbit/s: 27.6 Mbyte/s raw, so at least 50:1.
  const double ratio = rawBytes(frames) / static_cast<double>(video.bytes);
  EXPECT_GT(ratio, 50.0);
  const double kbps = 8.0 * static_cast<double>(video.bytes) / 1000.0;  // 30 frames = 1 s
  EXPECT_GT(kbps, 100.0);
  EXPECT_LT(kbps, 4000.0);
  // Lossy but faithful: PSNR above 30 dB on every frame.
  for (std::size_t k = 0; k < frames.size(); ++k)
    EXPECT_GT(cv::PSNR(frames[k], video.frames[k]), 30.0) << "frame " << k;
}

TEST(VideoCodecRoundTrip, JpegQualitySetsTheBytes) {
  std::vector<cv::Mat> frames = panningPhoto();
  frames.resize(3);
  const EncodedVideo low = roundTripVideo(frames, "mjpeg", 30.0, 30);
  const EncodedVideo high = roundTripVideo(frames, "mjpeg", 30.0, 95);
  ASSERT_EQ(low.frames.size(), 3u);
  EXPECT_LT(static_cast<double>(low.bytes), 0.5 * static_cast<double>(high.bytes));
  EXPECT_LT(cv::PSNR(frames[0], low.frames[0]), cv::PSNR(frames[0], high.frames[0]));
}

TEST(VideoCodecRoundTrip, RejectsUnknownCodecsAndMixedSizes) {
  const std::vector<cv::Mat> frames = {cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(9))};
  EXPECT_THROW(roundTripVideo(frames, "vp9000", 30.0), Error);
  EXPECT_THROW(roundTripVideo({frames[0], cv::Mat(32, 64, CV_8UC3)}, "h264", 30.0), Error);
  EXPECT_TRUE(roundTripVideo({}, "h264", 30.0).frames.empty());
}
