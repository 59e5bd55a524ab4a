#include "engine/dataset/EurocCamera.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <opencv2/core.hpp>
#include <sstream>

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

// The numbers of a sequence node `key` of sensor.yaml; throws naming the key unless it holds
// exactly `count` finite numbers.
std::vector<double> readNumbers(const cv::FileNode& node, const std::string& where,
                                const std::string& key, std::size_t count) {
  if (node.empty() || !node.isSeq())
    throw Error(where + ": '" + key + "' must be a list of " + std::to_string(count) + " numbers");
  std::vector<double> values;
  for (const cv::FileNode& v : node) {
    if (!v.isReal() && !v.isInt())
      throw Error(where + ": '" + key + "' must be a list of " + std::to_string(count) +
                  " numbers");
    values.push_back(static_cast<double>(v));
  }
  if (values.size() != count)
    throw Error(where + ": '" + key + "' holds " + std::to_string(values.size()) +
                " numbers, expected " + std::to_string(count));
  for (double v : values)
    if (!std::isfinite(v)) throw Error(where + ": '" + key + "' holds NaN or infinity");
  return values;
}

std::string readString(const cv::FileNode& node) {
  return node.isString() ? static_cast<std::string>(node) : std::string();
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
    if (!fs::is_regular_file(file))
      throw Error(where + ": image '" + file.string() + "' does not exist");
    previous = ns;
    frames.push_back({static_cast<double>(ns) * 1e-9, file});
  });
  if (frames.empty()) throw Error("EuRoC frame list '" + csv.string() + "' lists no frame");
  return frames;
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
  std::ifstream in(sensorYaml, std::ios::binary);
  if (!in) throw Error(where + " cannot be opened");
  std::stringstream text;
  text << in.rdbuf();
  // EuRoC's files carry no "%YAML:1.0" directive; openConfigText adds it and checks the text
  // against the YAML subset OpenCV's parser is safe on.
  const cv::FileStorage fs = openConfigText(text.str(), where, "is not valid YAML");
  const cv::FileNode root = fs.root();
  const std::string model = readString(root["camera_model"]);
  if (!model.empty() && model != "pinhole")
    throw Error(where + ": camera_model '" + model + "' is not supported (only pinhole)");
  const std::vector<double> k = readNumbers(root["intrinsics"], where, "intrinsics", 4);
  const std::vector<double> res = readNumbers(root["resolution"], where, "resolution", 2);
  std::vector<double> distortion;
  const std::string distortionModel = readString(root["distortion_model"]);
  if (distortionModel == "radial-tangential" || distortionModel == "radtan") {
    distortion = readNumbers(root["distortion_coefficients"], where, "distortion_coefficients", 4);
  } else if (!distortionModel.empty() || !root["distortion_coefficients"].empty()) {
    throw Error(where + ": distortion_model '" + distortionModel +
                "' is not supported (only radial-tangential [k1, k2, p1, p2])");
  }
  Eigen::Matrix3d K;
  K << k[0], 0, k[2], 0, k[1], k[3], 0, 0, 1;
  if (res[0] != std::round(res[0]) || res[1] != std::round(res[1]))
    throw Error(where + ": 'resolution' must be two whole numbers [width, height]");
  into.camera =
      PinholeCamera(K, cv::Size(static_cast<int>(res[0]), static_cast<int>(res[1])), distortion);
  try {
    into.camera.check();
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  const cv::FileNode tbs = root["T_BS"];
  if (tbs.empty() || !tbs.isMap())
    throw Error(where + ": 'T_BS' (sensor pose in the body frame: rows, cols, data) is missing");
  const std::vector<double> d = readNumbers(tbs["data"], where, "T_BS.data", 16);
  Eigen::Matrix4d T;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) T(r, c) = d[static_cast<std::size_t>(4 * r + c)];
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  if (T.row(3) != Eigen::RowVector4d(0, 0, 0, 1) ||
      (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-4 || R.determinant() < 0)
    throw Error(where + ": 'T_BS' is not a rigid transform (rotation and last row 0 0 0 1)");
  // Re-orthonormalise the printed rotation (8-10 digits) so inverses stay exact.
  into.sensorToBody = RigidPose(Eigen::Quaterniond(R).normalized(), T.topRightCorner<3, 1>());
  const cv::FileNode rate = root["rate_hz"];
  into.rateHz = rate.isReal() || rate.isInt() ? static_cast<double>(rate) : 0.0;
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
