#pragma once
// Writers of small dataset fixtures in the two public layouts the `tum:` and `euroc:` inputs read,
// so tests build them from the simulator (or from plain images) with exactly known content:
//   TUM RGB-D:  DIR/rgb/<t>.png, DIR/rgb.txt ("timestamp rgb/<t>.png"), DIR/groundtruth.txt
//               (TUM, camera in world);
//   EuRoC/ASL:  DIR/mav0/cam0/{data.csv, data/<ns>.png, sensor.yaml} and
//               DIR/mav0/state_groundtruth_estimate0/data.csv (body poses: camera * T_BS^-1).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <utility>
#include <vector>

#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/TumTrajectory.hpp"

namespace reftrack::test {

// `times` in seconds (written with 6 decimals, as TUM does); groundTruth may be empty.
inline void writeTumSequence(const std::filesystem::path& dir, const std::vector<cv::Mat>& images,
                             const std::vector<double>& times, const TumTrajectory& groundTruth) {
  std::filesystem::create_directories(dir / "rgb");
  std::ofstream list(dir / "rgb.txt");
  list << "# color images\n# file: 'fixture.bag'\n# timestamp filename\n";
  for (std::size_t k = 0; k < images.size(); ++k) {
    char stamp[64];
    std::snprintf(stamp, sizeof stamp, "%.6f", times[k]);
    const std::string name = std::string("rgb/") + stamp + ".png";
    cv::imwrite((dir / name).string(), images[k]);
    list << stamp << ' ' << name << '\n';
  }
  if (!groundTruth.poses.empty()) groundTruth.save(dir / "groundtruth.txt");
}

// The sensor.yaml text of a EuRoC camera, in the dataset's own format (no %YAML directive, T_BS as
// rows/cols/data, comments after values).
inline std::string eurocSensorYaml(const PinholeCamera& camera, const RigidPose& sensorToBody,
                                   double rateHz) {
  const Eigen::Matrix4d T = sensorToBody.matrix4();
  std::string text =
      "# General sensor definitions.\nsensor_type: camera\ncomment: VI-Sensor cam0 (MT9M034)\n\n"
      "# Sensor extrinsics wrt. the body-frame.\nT_BS:\n  cols: 4\n  rows: 4\n  data: [";
  char buf[128];  // four %.17g numbers: at most 4 * 24 + 6 characters
  for (int i = 0; i < 16; ++i) {
    std::snprintf(buf, sizeof buf, "%.17g%s", T(i / 4, i % 4), i == 15 ? "]\n" : ", ");
    text += buf;
    if (i % 4 == 3 && i != 15) text += "\n         ";
  }
  std::snprintf(buf, sizeof buf, "%g", rateHz);
  text += std::string("\n# Camera specific definitions.\nrate_hz: ") + buf + "\nresolution: [" +
          std::to_string(camera.imageSize().width) + ", " +
          std::to_string(camera.imageSize().height) + "]\ncamera_model: pinhole\nintrinsics: [";
  std::snprintf(buf, sizeof buf, "%.17g, %.17g, %.17g, %.17g", camera.fx(), camera.fy(),
                camera.cx(), camera.cy());
  text += std::string(buf) + "] #fu, fv, cu, cv\ndistortion_model: radial-tangential\n";
  std::vector<double> d = camera.distortion();
  d.resize(4, 0.0);
  std::snprintf(buf, sizeof buf, "%.17g, %.17g, %.17g, %.17g", d[0], d[1], d[2], d[3]);
  return text + "distortion_coefficients: [" + buf + "]\n";
}

// `ns`: frame timestamps in nanoseconds; groundTruth: (ns, world->camera) pairs, written as body
// poses p_RS_R, q_RS (w x y z) with zero velocities and biases; may be empty.
inline void writeEurocSequence(const std::filesystem::path& dir, const std::vector<cv::Mat>& images,
                               const std::vector<long long>& ns, const PinholeCamera& camera,
                               const RigidPose& sensorToBody,
                               const std::vector<std::pair<long long, RigidPose>>& groundTruth) {
  const std::filesystem::path cam = dir / "mav0" / "cam0";
  std::filesystem::create_directories(cam / "data");
  std::ofstream csv(cam / "data.csv");
  csv << "#timestamp [ns],filename\n";
  for (std::size_t k = 0; k < images.size(); ++k) {
    const std::string name = std::to_string(ns[k]) + ".png";
    cv::imwrite((cam / "data" / name).string(), images[k]);
    csv << ns[k] << ',' << name << "\r\n";  // EuRoC's lists end their lines with CR LF
  }
  std::ofstream(cam / "sensor.yaml") << eurocSensorYaml(camera, sensorToBody, 20.0);
  if (groundTruth.empty()) return;
  const std::filesystem::path gtDir = dir / "mav0" / "state_groundtruth_estimate0";
  std::filesystem::create_directories(gtDir);
  std::ofstream gt(gtDir / "data.csv");
  gt << "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], "
        "q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], b_w_RS_S_x "
        "[rad s^-1], b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m s^-2], "
        "b_a_RS_S_y [m s^-2], b_a_RS_S_z [m s^-2]\n";
  for (const auto& [t, worldToCamera] : groundTruth) {
    const RigidPose bodyToWorld = worldToCamera.inverse() * sensorToBody.inverse();
    const Eigen::Quaterniond q = bodyToWorld.quaternion();
    const Eigen::Vector3d& p = bodyToWorld.translation();
    char line[256];
    std::snprintf(line, sizeof line, "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", t, p.x(),
                  p.y(), p.z(), q.w(), q.x(), q.y(), q.z());
    gt << line << ",0,0,0,0,0,0,0,0,0\n";
  }
}

}  // namespace reftrack::test
