#pragma once
// StampedImageFile: one frame of a dataset's frame list, an image file with its timestamp
// (seconds, on the dataset's own clock).
#include <filesystem>

namespace reftrack {

struct StampedImageFile {
  double timestamp = 0.0;
  std::filesystem::path file;
};

}  // namespace reftrack
