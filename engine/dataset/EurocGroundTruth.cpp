#include "engine/dataset/EurocGroundTruth.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "engine/core/DataLines.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

TumTrajectory readEurocGroundTruth(const std::filesystem::path& csv,
                                   const RigidPose& sensorToBody) {
  std::ifstream in(csv);
  if (!in) throw Error("EuRoC ground truth '" + csv.string() + "' cannot be opened");
  TumTrajectory trajectory;
  long long previous = 0;
  forEachDataLine(in, [&](const std::string& line, int lineNo) {
    const std::string where = "EuRoC ground truth '" + csv.string() + "', line " +
                              std::to_string(lineNo) +
                              ": expected 'timestamp [ns], p_RS_R x y z, q_RS w x y z, ...'";
    std::vector<std::string> fields;
    std::stringstream ss(line);
    std::string field;
    while (std::getline(ss, field, ',')) fields.push_back(field);
    if (fields.size() < 8) throw Error(where);
    const auto b = fields[0].find_first_not_of(" \t"), e = fields[0].find_last_not_of(" \t\r");
    const std::string stamp = b == std::string::npos ? "" : fields[0].substr(b, e - b + 1);
    long long ns = 0;
    const auto [end, ec] = std::from_chars(stamp.data(), stamp.data() + stamp.size(), ns);
    if (stamp.empty() || ec != std::errc() || end != stamp.data() + stamp.size() || ns < 0)
      throw Error(where + " (an integer timestamp in ns)");
    if (!trajectory.poses.empty() && ns <= previous)
      throw Error("EuRoC ground truth '" + csv.string() + "', line " + std::to_string(lineNo) +
                  ": timestamp " + stamp + " does not increase");
    double v[7];
    for (int i = 0; i < 7; ++i) {
      char* endp = nullptr;
      v[i] = std::strtod(fields[static_cast<std::size_t>(i + 1)].c_str(), &endp);
      while (endp && (*endp == ' ' || *endp == '\t' || *endp == '\r')) ++endp;
      if (!endp || *endp != '\0' || !std::isfinite(v[i])) throw Error(where);
    }
    const Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-3)
      throw Error("EuRoC ground truth '" + csv.string() + "', line " + std::to_string(lineNo) +
                  ": quaternion q_RS is not unit length");
    const RigidPose bodyToWorld(q.normalized(), Eigen::Vector3d(v[0], v[1], v[2]));
    const RigidPose cameraToWorld = bodyToWorld * sensorToBody;
    trajectory.poses.push_back({static_cast<double>(ns) * 1e-9, cameraToWorld.inverse()});
    previous = ns;
  });
  if (trajectory.poses.empty())
    throw Error("EuRoC ground truth '" + csv.string() + "' holds no pose");
  return trajectory;
}

}  // namespace reftrack
