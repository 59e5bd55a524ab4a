#include "engine/dataset/EurocCamera.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <opencv2/core.hpp>

#include "engine/config/ConfigFile.hpp"
#include "engine/core/DataLines.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

namespace fs = std::filesystem;

namespace {

bool isCameraFolder(const fs::path& dir) {
  return fs::is_regular_file(dir / "data.csv") && fs::is_regular_file(dir / "sensor.yaml");
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// The numbers of the list `node` of sensor.yaml; throws naming its key and line unless it holds
// exactly `count` finite numbers.
std::vector<double> readNumbers(const YamlNode& node, std::size_t count) {
  const std::string list = "a list of " + std::to_string(count) + " numbers";
  if (!node.present()) throw Error("'" + node.name() + "' (" + list + ") is missing");
  if (!node.isList()) node.fail("'" + node.name() + "' must be " + list);
  std::vector<double> values;
  for (const YamlNode& v : node.children()) {
    if (!v.number()) v.fail("'" + node.name() + "' must be " + list);
    values.push_back(*v.number());
  }
  if (values.size() != count)
    node.fail("'" + node.name() + "' holds " + std::to_string(values.size()) +
              " numbers, expected " + std::to_string(count));
  for (double v : values)
    if (!std::isfinite(v)) node.fail("'" + node.name() + "' holds NaN or infinity");
  return values;
}

std::vector<StampedImageFile> readFrameList(const fs::path& folder) {
  const fs::path csv = folder / "data.csv";
  std::ifstream in(csv);
  if (!in) throw Error("EuRoC frame list '" + csv.string() + "' cannot be opened");
  std::vector<StampedImageFile> frames;
  long long previous = 0;
  forEachDataLine(in, [&](const std::string& line, int lineNo) {
    const std::string text = trim(line);
    const std::string where =
        "EuRoC frame list '" + csv.string() + "', line " + std::to_string(lineNo);
    const auto comma = text.find(',');
    if (comma == std::string::npos) throw Error(where + ": expected 'timestamp [ns],filename'");
    const std::string stamp = trim(text.substr(0, comma)), name = trim(text.substr(comma + 1));
    long long ns = 0;
    const auto [end, ec] = std::from_chars(stamp.data(), stamp.data() + stamp.size(), ns);
    if (stamp.empty() || ec != std::errc() || end != stamp.data() + stamp.size() || ns < 0 ||
        name.empty() || name.find(',') != std::string::npos)
      throw Error(where + ": expected 'timestamp [ns],filename' (an integer number of ns)");
    if (!frames.empty() && ns <= previous)
      throw Error(where + ": timestamp " + stamp + " does not increase");
    const fs::path file = folder / "data" / name;
    // A name the file system refuses (too long, ...) does not exist either.
    std::error_code unreadable;
    if (!fs::is_regular_file(file, unreadable))
      throw Error(where + ": image '" + file.string() + "' does not exist");
    previous = ns;
    frames.push_back({static_cast<double>(ns) * 1e-9, file});
  });
  if (frames.empty()) throw Error("EuRoC frame list '" + csv.string() + "' lists no frame");
  return frames;
}

// sensor.yaml's camera model, intrinsics, resolution, distortion, T_BS and rate.
void readSensorFields(const YamlNode& root, EurocCamera& into) {
  const YamlNode modelNode = root["camera_model"];
  const std::string model = modelNode.text().value_or("");
  if (!model.empty() && model != "pinhole")
    modelNode.fail("camera_model '" + model + "' is not supported (only pinhole)");
  const std::vector<double> k = readNumbers(root["intrinsics"], 4);
  const YamlNode resolution = root["resolution"];
  const std::vector<double> res = readNumbers(resolution, 2);
  std::vector<double> distortion;
  const YamlNode distortionNode = root["distortion_model"];
  const std::string distortionModel = distortionNode.text().value_or("");
  if (distortionModel == "radial-tangential" || distortionModel == "radtan") {
    distortion = readNumbers(root["distortion_coefficients"], 4);
  } else if (!distortionModel.empty() || root["distortion_coefficients"].present()) {
    distortionNode.fail("distortion_model '" + distortionModel +
                        "' is not supported (only radial-tangential [k1, k2, p1, p2])");
  }
  Eigen::Matrix3d K;
  K << k[0], 0, k[2], 0, k[1], k[3], 0, 0, 1;
  if (res[0] != std::round(res[0]) || res[1] != std::round(res[1]) || res[0] < 1 || res[1] < 1 ||
      res[0] > 1e5 || res[1] > 1e5)
    resolution.fail("'resolution' must be two whole numbers [width, height]");
  into.camera =
      PinholeCamera(K, cv::Size(static_cast<int>(res[0]), static_cast<int>(res[1])), distortion);
  into.camera.check();
  const YamlNode tbs = root["T_BS"];
  if (!tbs.isMap())
    throw Error("'T_BS' (sensor pose in the body frame: rows, cols, data) is missing");
  const std::vector<double> d = readNumbers(tbs["data"], 16);
  Eigen::Matrix4d T;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) T(r, c) = d[static_cast<std::size_t>(4 * r + c)];
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  if (T.row(3) != Eigen::RowVector4d(0, 0, 0, 1) ||
      (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-4 || R.determinant() < 0)
    tbs.fail("'T_BS' is not a rigid transform (rotation and last row 0 0 0 1)");
  // Re-orthonormalise the printed rotation (8-10 digits) so inverses stay exact.
  into.sensorToBody = RigidPose(Eigen::Quaterniond(R).normalized(), T.topRightCorner<3, 1>());
  into.rateHz = root["rate_hz"].number().value_or(0.0);
}

}  // namespace

fs::path EurocCamera::findFolder(const fs::path& given) {
  fs::path dir = given.lexically_normal();
  if (!dir.has_filename() && dir.has_parent_path()) dir = dir.parent_path();  // "cam0/"
  if (isCameraFolder(dir)) return dir;
  for (const fs::path& candidate : {dir / "mav0" / "cam0", dir / "cam0"})
    if (isCameraFolder(candidate)) return candidate;
  throw Error("EuRoC folder '" + given.string() +
              "': expected DIR/mav0/cam0, DIR/cam0 or a camera folder, each holding data.csv and "
              "sensor.yaml");
}

void EurocCamera::readSensor(const fs::path& sensorYaml, EurocCamera& into) {
  const std::string where = "EuRoC sensor file '" + sensorYaml.string() + "'";
  if (!fs::is_regular_file(sensorYaml)) throw Error(where + " cannot be opened");
  const YamlNode root = readConfigFile(sensorYaml, where);
  try {
    readSensorFields(root, into);
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
}

EurocCamera EurocCamera::open(const fs::path& dir) {
  EurocCamera cam;
  cam.folder = findFolder(dir);
  readSensor(cam.folder / "sensor.yaml", cam);
  cam.frames = readFrameList(cam.folder);
  return cam;
}

fs::path EurocCamera::groundTruthFile() const {
  return folder.parent_path() / "state_groundtruth_estimate0" / "data.csv";
}

}  // namespace reftrack
