#pragma once
// VideoCodecRoundTrip: frames through a real video codec and back, as a webcam stream arrives —
// h264 (avc1) and mp4v through OpenCV's FFmpeg VideoWriter / VideoCapture (a temporary MP4, the
// first frame a key frame; OpenCV 4.6 chooses the bitrate itself: x264's default quality for
// h264), or mjpeg: every frame a JPEG of the given quality (cv::imencode), what USB webcams send.
#include <cstddef>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace reftrack::app {

struct EncodedVideo {
  std::vector<cv::Mat> frames;  // decoded, CV_8UC3, as many as were encoded
  std::size_t bytes = 0;        // size of the encoded stream (the MP4 file, or the JPEGs)
};

// `frames`: CV_8UC3, all of one size. codec: h264 | mp4v | mjpeg. Throws reftrack::Error when the
// codec is unknown or unavailable, or when the decoder does not give every frame back.
EncodedVideo roundTripVideo(const std::vector<cv::Mat>& frames, const std::string& codec,
                            double fps, int jpegQuality = 75);

}  // namespace reftrack::app
