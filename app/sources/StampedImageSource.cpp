#include "app/sources/StampedImageSource.hpp"

#include <cstdio>
#include <opencv2/imgcodecs.hpp>

#include "engine/core/Error.hpp"

namespace reftrack::app {

StampedImageSource::StampedImageSource(std::vector<StampedImageFile> frames, std::string name)
    : frames_(std::move(frames)), name_(std::move(name)) {
  if (frames_.empty()) throw Error(name_ + " lists no frame");
  const double span = frames_.back().timestamp - frames_.front().timestamp;
  if (frames_.size() > 1 && span > 0) fps_ = static_cast<double>(frames_.size() - 1) / span;
}

std::optional<Frame> StampedImageSource::next() {
  if (nextIndex_ >= static_cast<int>(frames_.size())) return std::nullopt;
  const StampedImageFile& f = frames_[static_cast<std::size_t>(nextIndex_)];
  cv::Mat image;
  try {
    image = cv::imread(f.file.string(), cv::IMREAD_COLOR);  // grey images become BGR
  } catch (const cv::Exception& e) {
    throw Error("image '" + f.file.string() + "' cannot be read: " + e.err);
  }
  if (image.empty())
    throw Error("image '" + f.file.string() +
                "' cannot be read (missing, corrupt or not an image)");
  if (firstSize_.area() == 0) firstSize_ = image.size();
  if (image.size() != firstSize_)
    throw Error("image '" + f.file.string() + "' is " + std::to_string(image.cols) + "x" +
                std::to_string(image.rows) + " but the first frame of " + name_ + " is " +
                std::to_string(firstSize_.width) + "x" + std::to_string(firstSize_.height));
  Frame frame{image, nextIndex_, f.timestamp};
  ++nextIndex_;
  return frame;
}

void StampedImageSource::seek(int index) {
  if (index < 0 || index >= static_cast<int>(frames_.size()))
    throw Error(description() + ": frame " + std::to_string(index) + " is out of range");
  nextIndex_ = index;
}

std::string StampedImageSource::description() const {
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.1f", fps_);
  return name_ + " (" + std::to_string(frames_.size()) + " frames, " + rate + " fps)";
}

}  // namespace reftrack::app
