#pragma once
// ImageFolderSource: the images of a folder (png, jpg, jpeg, bmp, tif, tiff, ppm, pgm) or of a
// glob pattern ("frames/*.png"), in natural order (frame2 before frame10), at a nominal frame
// rate. Images are read one at a time; an unreadable image or (unless anySizes) one whose size
// differs from the first throws reftrack::Error naming the file. Grey images are converted to
// BGR.
#include <filesystem>
#include <string>
#include <vector>

#include "app/sources/FrameSource.hpp"

namespace reftrack::app {

// Natural ordering of file names: digit runs compare by value ("img2" < "img10").
bool naturalLess(const std::string& a, const std::string& b);

class ImageFolderSource final : public FrameSource {
 public:
  // `folderOrGlob`: a folder, or a pattern with * ? in its last component. anySizes: images may
  // differ in size (photos from several cameras). Throws reftrack::Error when the folder does
  // not exist or no image matches.
  explicit ImageFolderSource(const std::string& folderOrGlob, double fps = 30.0,
                             bool anySizes = false);

  std::optional<Frame> next() override;
  std::optional<int> frameCount() const override { return static_cast<int>(files_.size()); }
  double fps() const override { return fps_; }
  bool seekable() const override { return true; }
  void seek(int index) override;
  std::string description() const override;

  const std::vector<std::filesystem::path>& files() const { return files_; }

 private:
  std::string spec_;
  std::vector<std::filesystem::path> files_;
  double fps_;
  bool anySizes_ = false;
  int nextIndex_ = 0;
  cv::Size firstSize_{0, 0};
};

}  // namespace reftrack::app
