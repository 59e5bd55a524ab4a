#pragma once
// loadGroundTruth: camera poses of a recording for `eval --gt` and `prepare --poses`, from
//   FILE        a TUM trajectory file (timestamp tx ty tz qx qy qz qw, camera in world), as is;
//   tum:DIR     a TUM RGB-D sequence: DIR/groundtruth.txt interpolated at the frame times of
//               DIR/rgb.txt (so every frame has its pose, and frames outside the motion capture
//               have none);
//   euroc:DIR   a EuRoC / ASL sequence: mav0/state_groundtruth_estimate0/data.csv (body poses),
//               through cam0's T_BS (sensor.yaml) to camera poses, interpolated at the cam0 frame
//               times of data.csv.
// Poses are interpolated only between ground-truth samples at most maxGap seconds apart.
// Throws reftrack::Error naming the missing or malformed file.
#include <string>

#include "engine/geometry/TumTrajectory.hpp"

namespace reftrack {

struct GroundTruth {
  TumTrajectory trajectory;  // world->camera per timestamp
  std::string description;   // where it came from, for the command's output
};

GroundTruth loadGroundTruth(const std::string& spec, double maxGap = 0.05);

}  // namespace reftrack
