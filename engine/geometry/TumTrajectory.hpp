#pragma once
// TUM trajectory files: one line per pose, `timestamp tx ty tz qx qy qz qw`, giving the
// camera pose in the world (camera->world: the camera centre and orientation). '#' lines are
// comments. Stamped poses here hold the world->camera pose T_k used by the tracker and renderer;
// conversion happens on read and write.
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <vector>

#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

struct StampedPose {
  double timestamp = 0.0;
  RigidPose worldToCamera;
};

class TumTrajectory {
 public:
  std::vector<StampedPose> poses;

  // Throws reftrack::Error naming the file and line of a malformed entry.
  static TumTrajectory load(const std::filesystem::path& file);
  void save(const std::filesystem::path& file) const;  // atomic
  // The file's comment header and one pose line, as save() writes them (for streamed writers).
  static void writeHeader(std::ostream& out);
  static void writeLine(std::ostream& out, const StampedPose& pose);
  // The pose whose timestamp is within `tolerance` of `t` (nearest), if any.
  std::optional<RigidPose> poseAt(double t, double tolerance = 1e-4) const;
};

}  // namespace reftrack
