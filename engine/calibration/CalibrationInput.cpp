#include "engine/calibration/CalibrationInput.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

bool hasImageExtension(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const std::vector<std::string> known = {".png",  ".jpg", ".jpeg", ".bmp", ".tif",
                                                 ".tiff", ".pgm", ".ppm",  ".webp"};
  return std::find(known.begin(), known.end(), ext) != known.end();
}

}  // namespace

CalibrationInput::CalibrationInput(const std::string& source, int maxVideoFrames) {
  namespace fs = std::filesystem;
  if (maxVideoFrames < 1) throw Error("calibration input: maxVideoFrames must be at least 1");
  const bool isPattern = source.find_first_of("*?") != std::string::npos;
  if (isPattern) {
    std::vector<cv::String> matches;
    try {
      cv::glob(source, matches, false);
    } catch (const cv::Exception&) {
      matches.clear();
    }
    for (const auto& m : matches)
      if (hasImageExtension(std::string(m))) files_.emplace_back(m);
    if (files_.empty()) throw Error("input '" + source + "' matches no image files");
  } else if (fs::is_directory(source)) {
    for (const auto& entry : fs::directory_iterator(source))
      if (entry.is_regular_file() && hasImageExtension(entry.path()))
        files_.push_back(entry.path().string());
    if (files_.empty()) throw Error("input folder '" + source + "' holds no image files");
  } else if (!fs::exists(source)) {
    throw Error("input '" + source + "' does not exist");
  } else if (hasImageExtension(source)) {
    files_.push_back(source);
  } else {
    // FFmpeg only: the GStreamer backend prints assertion noise on files it cannot open.
    video_ = std::make_unique<cv::VideoCapture>(source, cv::CAP_FFMPEG);
    if (!video_->isOpened())
      throw Error("input '" + source + "' is neither an image nor a readable video");
    const double count = video_->get(cv::CAP_PROP_FRAME_COUNT);
    if (std::isfinite(count) && count > 0) {
      videoStep_ = std::max(1, static_cast<int>(std::ceil(count / maxVideoFrames)));
      size_ = static_cast<std::size_t>(std::ceil(count / videoStep_));
    }
  }
  std::sort(files_.begin(), files_.end());
  if (!video_) size_ = files_.size();
}

bool CalibrationInput::next(cv::Mat& image, std::string& label) {
  if (video_) {
    if (videoFrame_ > 0)
      for (int i = 1; i < videoStep_; ++i)
        if (!video_->grab()) return false;
    if (!video_->read(image) || image.empty()) return false;
    label = "frame " + std::to_string(videoFrame_ * videoStep_);
    ++videoFrame_;
    return true;
  }
  if (nextFile_ >= files_.size()) return false;
  const std::string& file = files_[nextFile_++];
  image = cv::imread(file, cv::IMREAD_GRAYSCALE);
  if (image.empty()) throw Error("image '" + file + "' cannot be read");
  label = std::filesystem::path(file).filename().string();
  return true;
}

}  // namespace reftrack
