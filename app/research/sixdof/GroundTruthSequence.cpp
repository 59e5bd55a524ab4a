#include "app/research/sixdof/GroundTruthSequence.hpp"

#include <algorithm>
#include <filesystem>
#include <memory>

#include "app/sources/FrameSourceFactory.hpp"
#include "app/sources/ImageFolderSource.hpp"
#include "app/sources/InputCamera.hpp"
#include "engine/core/Error.hpp"
#include "engine/dataset/DatasetGroundTruth.hpp"
#include "engine/dataset/DatasetSpec.hpp"
#include "engine/evaluation/TrajectoryInterpolation.hpp"

namespace reftrack::app {

namespace {

// Ground-truth samples farther apart than this are not interpolated across (s), as in `prepare`.
constexpr double kMaxGroundTruthGap = 0.05;
// A frame this close to a ground-truth sample (s) has that sample's pose.
constexpr double kSampleTolerance = 1e-4;

std::string sizeText(cv::Size s) {
  return std::to_string(s.width) + "x" + std::to_string(s.height);
}

}  // namespace

int GroundTruthSequence::truthCount() const {
  return static_cast<int>(
      std::count_if(truth.begin(), truth.end(), [](const auto& t) { return t.has_value(); }));
}

GroundTruthSequence loadGroundTruthSequence(const GroundTruthSequenceSpec& spec) {
  const bool dataset = parseDatasetSpec(spec.input).has_value();  // throws for a missing DIR
  if (!dataset && spec.input.find_first_of("*?[") == std::string::npos &&
      !std::filesystem::exists(spec.input))
    throw Error("input '" + spec.input +
                "' not found (an image folder, a video, tum:DIR or euroc:DIR)");
  GroundTruthSequence s;
  if (spec.camera.empty()) {
    const std::optional<PinholeCamera> brought = cameraFromInput(spec.input);
    if (!brought)
      throw Error("input '" + spec.input +
                  "' brings no camera: give its camera.yml (only euroc: inputs bring theirs)");
    s.camera = *brought;
    s.cameraDescription = "the sensor.yaml of '" + spec.input + "'";
  } else {
    if (!std::filesystem::is_regular_file(spec.camera))
      throw Error("camera file '" + spec.camera + "' not found");
    s.camera = PinholeCamera::load(spec.camera);
    s.cameraDescription = "camera file '" + spec.camera + "'";
  }
  std::string groundTruthSpec = spec.groundTruth;
  if (groundTruthSpec.empty()) {
    if (!dataset)
      throw Error("input '" + spec.input +
                  "' brings no ground truth: give a TUM trajectory file (only tum: and euroc: "
                  "inputs bring theirs)");
    groundTruthSpec = spec.input;
  } else if (!parseDatasetSpec(groundTruthSpec) &&
             !std::filesystem::is_regular_file(groundTruthSpec)) {
    throw Error("ground-truth file '" + groundTruthSpec + "' not found");
  }

  if (spec.firstFrame < 0) throw Error("the first frame must be >= 0");
  const std::unique_ptr<FrameSource> source = openFrameSource(spec.input);
  s.framesDescription = source->description();
  s.firstFrame = spec.firstFrame;
  const std::optional<int> count = source->frameCount();
  if (spec.firstFrame > 0 && count && spec.firstFrame >= *count)
    throw Error(s.framesDescription + " holds " + std::to_string(*count) +
                " frames: none from frame " + std::to_string(spec.firstFrame) + " on");
  // An image folder seeks exactly (the frames keep their indices and timestamps); a video's seek
  // may land near the frame, so videos and datasets are read up to it.
  if (spec.firstFrame > 0 && dynamic_cast<ImageFolderSource*>(source.get()) != nullptr)
    source->seek(spec.firstFrame);
  else
    for (int k = 0; k < spec.firstFrame; ++k)
      if (!source->next())
        throw Error(s.framesDescription + " ends before frame " + std::to_string(spec.firstFrame));
  while (spec.frames <= 0 || static_cast<int>(s.frames.size()) < spec.frames) {
    std::optional<Frame> frame = source->next();
    if (!frame) break;
    if (frame->image.size() != s.camera.imageSize())
      throw Error("frame " + std::to_string(frame->index) + " of " + s.framesDescription + " is " +
                  sizeText(frame->image.size()) + " but " + s.cameraDescription + " is for " +
                  sizeText(s.camera.imageSize()) + " images");
    s.timestamps.push_back(frame->timestamp);
    s.frames.push_back(std::move(frame->image));
  }
  if (s.frames.empty())
    throw Error(s.framesDescription + " holds no frames" +
                (spec.firstFrame > 0 ? " from frame " + std::to_string(spec.firstFrame) + " on"
                                     : std::string()));

  const GroundTruth gt = loadGroundTruth(groundTruthSpec, kMaxGroundTruthGap);
  s.groundTruthDescription = gt.description;
  // The resampled trajectory keeps the frames' order and their exact times, skipping the frames
  // the ground truth does not cover.
  const TumTrajectory atFrames =
      interpolateTrajectory(gt.trajectory, s.timestamps, kMaxGroundTruthGap);
  // A frame within 0.1 ms of a sample outside their span (the last sample's time written with 6
  // decimals: 0.133333 for frame 4 at 4 / 30 s) takes that sample.
  std::size_t next = 0;
  for (double t : s.timestamps) {
    if (next < atFrames.poses.size() && atFrames.poses[next].timestamp == t)
      s.truth.push_back(atFrames.poses[next++].worldToCamera);
    else
      s.truth.push_back(gt.trajectory.poseAt(t, kSampleTolerance));
  }
  if (s.truthCount() == 0)
    throw Error(gt.description + " gives none of the " + std::to_string(s.frames.size()) +
                " frames of " + s.framesDescription +
                " a pose: check the time bases (an image folder's frame k is at k / 30 s)");
  return s;
}

}  // namespace reftrack::app
