#pragma once
// GroundTruthSequence: a recording with a true camera pose per frame, as `bench-real --input`
// reads it: the frames of an image folder, a video, tum:DIR or euroc:DIR (openFrameSource: a
// folder's frame k at k / 30 s, a video's at k / its rate, a dataset's at its own timestamps),
// the camera (a camera.yml, or the sensor.yaml a euroc: input brings), and the ground truth at
// each frame's timestamp (loadGroundTruth: a TUM file, or for tum:/euroc: the dataset's own;
// interpolated between samples at most 0.05 s apart, as `prepare --poses` does; a frame within
// 0.1 ms of a sample but outside the samples' span, e.g. the last frame of a file with rounded
// times, takes that sample).
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack::app {

struct GroundTruthSequenceSpec {
  std::string input;        // image folder, glob, video, tum:DIR or euroc:DIR
  std::string camera;       // camera.yml; "" for a euroc: input (its sensor.yaml)
  std::string groundTruth;  // TUM file, tum:DIR or euroc:DIR; "" for the input's own (tum:/euroc:)
  int frames = 0;           // read `frames` frames from firstFrame on; 0: all to the end
  int firstFrame = 0;       // skip the frames before this one (the input's frame index)
};

struct GroundTruthSequence {
  std::string framesDescription, cameraDescription, groundTruthDescription;
  PinholeCamera camera;
  int firstFrame = 0;  // the input's index of frames[0] (spec.firstFrame)
  std::vector<cv::Mat>
      frames;  // BGR, the camera's image size; frames[k] is input frame firstFrame + k
  std::vector<double> timestamps;
  std::vector<std::optional<RigidPose>> truth;  // world->camera per frame; none where uncovered

  int truthCount() const;  // frames with a true pose
};

// Throws reftrack::Error naming what is missing or wrong: an input, camera or ground-truth file
// that does not exist, no --camera for an input that brings none, no ground truth for an input
// that brings none, a frame whose size is not the camera's, no frame at or after firstFrame, or
// ground truth covering no frame.
GroundTruthSequence loadGroundTruthSequence(const GroundTruthSequenceSpec& spec);

}  // namespace reftrack::app
