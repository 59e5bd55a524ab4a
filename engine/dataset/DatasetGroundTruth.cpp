#include "engine/dataset/DatasetGroundTruth.hpp"

#include "engine/core/Error.hpp"
#include "engine/dataset/DatasetSpec.hpp"
#include "engine/dataset/EurocCamera.hpp"
#include "engine/dataset/EurocGroundTruth.hpp"
#include "engine/dataset/TumRgbList.hpp"
#include "engine/evaluation/TrajectoryInterpolation.hpp"

namespace reftrack {

namespace {

std::vector<double> timesOf(const std::vector<StampedImageFile>& frames) {
  std::vector<double> t;
  for (const StampedImageFile& f : frames) t.push_back(f.timestamp);
  return t;
}

std::string resampledNote(const TumTrajectory& samples, const TumTrajectory& resampled,
                          std::size_t frames, const std::string& frameList) {
  return std::to_string(samples.poses.size()) + " samples interpolated at " +
         std::to_string(resampled.poses.size()) + " of the " + std::to_string(frames) +
         " frame times of " + frameList;
}

}  // namespace

GroundTruth loadGroundTruth(const std::string& spec, double maxGap) {
  const std::optional<DatasetSpec> dataset = parseDatasetSpec(spec);
  GroundTruth gt;
  if (!dataset) {
    gt.trajectory = TumTrajectory::load(spec);
    gt.description =
        "TUM trajectory '" + spec + "' (" + std::to_string(gt.trajectory.poses.size()) + " poses)";
    return gt;
  }
  if (dataset->layout == DatasetLayout::Tum) {
    const std::filesystem::path file = dataset->dir / "groundtruth.txt";
    if (!std::filesystem::is_regular_file(file))
      throw Error("TUM RGB-D folder '" + dataset->dir.string() + "' has no groundtruth.txt");
    const std::vector<StampedImageFile> frames = readTumRgbList(dataset->dir);
    const TumTrajectory samples = TumTrajectory::load(file);
    gt.trajectory = interpolateTrajectory(samples, timesOf(frames), maxGap);
    gt.description = "TUM RGB-D ground truth '" + file.string() +
                     "': " + resampledNote(samples, gt.trajectory, frames.size(), "rgb.txt");
  } else {
    const EurocCamera camera = EurocCamera::open(dataset->dir);
    const std::filesystem::path file = camera.groundTruthFile();
    if (!std::filesystem::is_regular_file(file))
      throw Error("EuRoC folder '" + dataset->dir.string() + "' has no ground truth '" +
                  file.string() + "'");
    const TumTrajectory samples = readEurocGroundTruth(file, camera.sensorToBody);
    gt.trajectory = interpolateTrajectory(samples, timesOf(camera.frames), maxGap);
    gt.description = "EuRoC ground truth '" + file.string() +
                     "' (body poses, camera = T_RS * T_BS of " +
                     (camera.folder / "sensor.yaml").string() + "): " +
                     resampledNote(samples, gt.trajectory, camera.frames.size(),
                                   (camera.folder / "data.csv").string());
  }
  if (gt.trajectory.poses.empty())
    throw Error("ground truth '" + spec + "' covers none of the frame times (" + gt.description +
                "); check the time bases");
  return gt;
}

}  // namespace reftrack
