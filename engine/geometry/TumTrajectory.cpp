#include "engine/geometry/TumTrajectory.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "engine/core/AtomicFile.hpp"
#include "engine/core/DataLines.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

TumTrajectory TumTrajectory::load(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw Error("trajectory file '" + file.string() + "' cannot be opened");
  TumTrajectory traj;
  forEachDataLine(in, [&](const std::string& line, int lineNo) {
    std::istringstream ss(line);
    double v[8];
    std::string token;
    for (double& x : v) {
      char* end = nullptr;
      if (ss >> token) x = std::strtod(token.c_str(), &end);
      if (!end || *end != '\0')
        throw Error("trajectory file '" + file.string() + "', line " + std::to_string(lineNo) +
                    ": expected 8 numbers 'timestamp tx ty tz qx qy qz qw'");
    }
    for (double x : v)
      if (!std::isfinite(x))
        throw Error("trajectory file '" + file.string() + "', line " + std::to_string(lineNo) +
                    ": NaN or infinite value");
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-3)
      throw Error("trajectory file '" + file.string() + "', line " + std::to_string(lineNo) +
                  ": quaternion is not unit length");
    RigidPose cameraToWorld(q, Eigen::Vector3d(v[1], v[2], v[3]));
    traj.poses.push_back({v[0], cameraToWorld.inverse()});
  });
  return traj;
}

void TumTrajectory::writeHeader(std::ostream& out) {
  out << "# timestamp tx ty tz qx qy qz qw (camera pose in the world, TUM format)\n";
}

void TumTrajectory::writeLine(std::ostream& out, const StampedPose& p) {
  const RigidPose c2w = p.worldToCamera.inverse();
  const Eigen::Quaterniond q = c2w.quaternion();
  const Eigen::Vector3d& t = c2w.translation();
  out << std::fixed << std::setprecision(6) << p.timestamp << std::defaultfloat
      << std::setprecision(17) << ' ' << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.x()
      << ' ' << q.y() << ' ' << q.z() << ' ' << q.w() << '\n';
}

void TumTrajectory::save(const std::filesystem::path& file) const {
  writeFileAtomically(file, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp);
    writeHeader(out);
    for (const StampedPose& p : poses) writeLine(out, p);
    out.close();  // flushes: a full disk shows here
    if (!out) throw Error("cannot write trajectory file '" + file.string() + "'");
  });
}

std::optional<RigidPose> TumTrajectory::poseAt(double t, double tolerance) const {
  const StampedPose* best = nullptr;
  for (const StampedPose& p : poses)
    if (!best || std::abs(p.timestamp - t) < std::abs(best->timestamp - t)) best = &p;
  if (best && std::abs(best->timestamp - t) <= tolerance) return best->worldToCamera;
  return std::nullopt;
}

}  // namespace reftrack
