#include "app/simulator/VideoCodecRoundTrip.hpp"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

namespace fs = std::filesystem;

// Removes the temporary file however the round trip ends.
struct TemporaryFile {
  fs::path path;
  ~TemporaryFile() {
    std::error_code ignored;
    fs::remove(path, ignored);
  }
};

fs::path temporaryVideoPath() {
  static std::atomic<unsigned> counter{0};
  return fs::temp_directory_path() / ("reftrack-codec-" + std::to_string(::getpid()) + "-" +
                                      std::to_string(counter++) + ".mp4");
}

EncodedVideo roundTripJpeg(const std::vector<cv::Mat>& frames, int quality) {
  EncodedVideo out;
  std::vector<uchar> buffer;
  for (const cv::Mat& frame : frames) {
    if (!cv::imencode(".jpg", frame, buffer, {cv::IMWRITE_JPEG_QUALITY, quality}))
      throw Error("mjpeg: cannot encode a frame");
    out.bytes += buffer.size();
    cv::Mat decoded = cv::imdecode(buffer, cv::IMREAD_COLOR);
    if (decoded.empty()) throw Error("mjpeg: cannot decode a frame");
    out.frames.push_back(decoded);
  }
  return out;
}

}  // namespace

EncodedVideo roundTripVideo(const std::vector<cv::Mat>& frames, const std::string& codec,
                            double fps, int jpegQuality) {
  if (frames.empty()) return {};
  for (const cv::Mat& f : frames)
    if (f.type() != CV_8UC3 || f.size() != frames.front().size())
      throw Error("video codec: frames must be CV_8UC3 and all of one size");
  if (codec == "mjpeg") return roundTripJpeg(frames, jpegQuality);
  int fourcc = 0;
  if (codec == "h264")
    fourcc = cv::VideoWriter::fourcc('a', 'v', 'c', '1');
  else if (codec == "mp4v")
    fourcc = cv::VideoWriter::fourcc('m', 'p', '4', 'v');
  else
    throw Error("video codec '" + codec + "' is unknown (h264, mp4v, mjpeg)");
  const TemporaryFile file{temporaryVideoPath()};
  {
    cv::VideoWriter writer(file.path.string(), cv::CAP_FFMPEG, fourcc, fps, frames.front().size());
    if (!writer.isOpened())
      throw Error("video codec '" + codec + "' is not available in OpenCV's FFmpeg writer");
    for (const cv::Mat& f : frames) writer.write(f);
  }
  EncodedVideo out;
  out.bytes = static_cast<std::size_t>(fs::file_size(file.path));
  cv::VideoCapture reader(file.path.string(), cv::CAP_FFMPEG);
  if (!reader.isOpened()) throw Error("video codec '" + codec + "': cannot read the encoded video");
  for (cv::Mat f; out.frames.size() < frames.size() && reader.read(f);)
    out.frames.push_back(f.clone());
  if (out.frames.size() != frames.size())
    throw Error("video codec '" + codec + "': decoded " + std::to_string(out.frames.size()) +
                " of " + std::to_string(frames.size()) + " frames");
  return out;
}

}  // namespace reftrack::app
