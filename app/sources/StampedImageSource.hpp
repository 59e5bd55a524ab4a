#pragma once
// StampedImageSource: the frames of a dataset's frame list — image files each with its own
// timestamp — read one at a time; frames keep the listed timestamps (seconds on the dataset's
// clock), so every output (trajectory, CSV, recording) can be set beside the dataset's ground
// truth. fps() is the mean rate of the list. Grey images are converted to BGR; an unreadable
// image, or one whose size differs from the first, throws reftrack::Error naming the file.
#include <string>
#include <vector>

#include "app/sources/FrameSource.hpp"
#include "engine/dataset/StampedImageFile.hpp"

namespace reftrack::app {

class StampedImageSource : public FrameSource {
 public:
  // `name`: how description() names the list, e.g. "TUM RGB-D 'fr1_xyz'". Throws reftrack::Error
  // for an empty list.
  StampedImageSource(std::vector<StampedImageFile> frames, std::string name);

  std::optional<Frame> next() override;
  std::optional<int> frameCount() const override { return static_cast<int>(frames_.size()); }
  double fps() const override { return fps_; }
  bool seekable() const override { return true; }
  void seek(int index) override;
  std::string description() const override;

  const std::vector<StampedImageFile>& frames() const { return frames_; }

 private:
  std::vector<StampedImageFile> frames_;
  std::string name_;
  double fps_ = 30.0;
  int nextIndex_ = 0;
  cv::Size firstSize_{0, 0};
};

}  // namespace reftrack::app
