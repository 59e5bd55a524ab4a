#pragma once
// EurocCamera: one camera of a EuRoC / ASL sequence (mav0/cam0): its frame list data.csv
// (`#timestamp [ns],filename`, images under data/) and its sensor.yaml — camera_model pinhole,
// intrinsics [fu, fv, cu, cv], distortion_model radial-tangential with distortion_coefficients
// [k1, k2, p1, p2], resolution [width, height], rate_hz, and T_BS, the sensor's pose in the body
// (IMU) frame as a row-major 4x4 (X_body = T_BS * X_sensor).
#include <filesystem>
#include <vector>

#include "engine/dataset/StampedImageFile.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

struct EurocCamera {
  std::filesystem::path folder;          // the camera folder, e.g. SEQ/mav0/cam0
  std::vector<StampedImageFile> frames;  // data.csv in order; seconds = nanoseconds * 1e-9
  PinholeCamera camera;                  // intrinsics, distortion and resolution of sensor.yaml
  RigidPose sensorToBody;                // T_BS
  double rateHz = 0.0;                   // rate_hz (0 when absent)

  // DIR: the sequence root (holding mav0/), mav0 itself, or the camera folder. Throws
  // reftrack::Error naming the missing file or the bad field of data.csv or sensor.yaml.
  static EurocCamera open(const std::filesystem::path& dir);
  // The camera folder DIR designates (see open); throws reftrack::Error when there is none.
  static std::filesystem::path findFolder(const std::filesystem::path& dir);
  // Reads sensor.yaml alone (camera and T_BS into `into`).
  static void readSensor(const std::filesystem::path& sensorYaml, EurocCamera& into);
  // The sequence's ground-truth file beside the camera folder (mav0/state_groundtruth_estimate0/
  // data.csv); it may not exist.
  std::filesystem::path groundTruthFile() const;
};

}  // namespace reftrack
