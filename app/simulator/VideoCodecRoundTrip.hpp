#pragma once
// VideoCodecRoundTrip: frames through a real video codec and back, as a webcam stream arrives —
// h264 (x264's defaults, constant quality 23, the first frame a key frame) and mp4v (MPEG-4 Part
// 2 at width x height x fps bit/s, a key frame every 12), the settings OpenCV 4.6's writer chose,
// through libavcodec in memory with settings fixed so that the result is the same on any machine
// (one thread each way, x264's SSE2 code; see the .cpp); or mjpeg: every frame a JPEG of the
// given quality (cv::imencode), what USB webcams send.
#include <cstddef>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace reftrack::app {

struct EncodedVideo {
  std::vector<cv::Mat> frames;  // decoded, CV_8UC3, as many as were encoded
  std::size_t bytes = 0;        // size of the encoded stream (its packets, or the JPEGs)
};

// `frames`: CV_8UC3, all of one size (odd sides are padded for 4:2:0 and cropped back). codec:
// h264 | mp4v | mjpeg. Throws reftrack::Error when the codec is unknown or unavailable, or when
// the decoder does not give every frame back.
EncodedVideo roundTripVideo(const std::vector<cv::Mat>& frames, const std::string& codec,
                            double fps, int jpegQuality = 75);

}  // namespace reftrack::app
