#pragma once
// EurocSequenceSource: the frames of one camera of a EuRoC / ASL sequence (`--input euroc:DIR`,
// DIR the sequence root, mav0 or the camera folder; cam0 by default): data.csv lists
// `timestamp [ns],filename`; frames carry the timestamps in seconds. The camera (intrinsics,
// radial-tangential distortion, resolution) and T_BS come from sensor.yaml. Throws
// reftrack::Error naming the file at fault for a bad layout (see EurocCamera).
#include <filesystem>

#include "app/sources/StampedImageSource.hpp"
#include "engine/dataset/EurocCamera.hpp"

namespace reftrack::app {

class EurocSequenceSource final : public StampedImageSource {
 public:
  explicit EurocSequenceSource(const std::filesystem::path& dir);

  const PinholeCamera& camera() const { return dataset_.camera; }
  const EurocCamera& dataset() const { return dataset_; }

 private:
  explicit EurocSequenceSource(EurocCamera dataset);
  EurocCamera dataset_;
};

}  // namespace reftrack::app
