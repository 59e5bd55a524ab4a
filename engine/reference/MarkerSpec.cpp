#include "engine/reference/MarkerSpec.hpp"

#include <cmath>
#include <opencv2/aruco.hpp>
#include <sstream>
#include <utility>
#include <vector>

#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

const std::vector<std::pair<std::string, int>>& dictionaries() {
  using namespace cv::aruco;
  static const std::vector<std::pair<std::string, int>> table = {
      {"DICT_4X4_50", DICT_4X4_50},
      {"DICT_4X4_100", DICT_4X4_100},
      {"DICT_4X4_250", DICT_4X4_250},
      {"DICT_4X4_1000", DICT_4X4_1000},
      {"DICT_5X5_50", DICT_5X5_50},
      {"DICT_5X5_100", DICT_5X5_100},
      {"DICT_5X5_250", DICT_5X5_250},
      {"DICT_5X5_1000", DICT_5X5_1000},
      {"DICT_6X6_50", DICT_6X6_50},
      {"DICT_6X6_100", DICT_6X6_100},
      {"DICT_6X6_250", DICT_6X6_250},
      {"DICT_6X6_1000", DICT_6X6_1000},
      {"DICT_7X7_50", DICT_7X7_50},
      {"DICT_7X7_100", DICT_7X7_100},
      {"DICT_7X7_250", DICT_7X7_250},
      {"DICT_7X7_1000", DICT_7X7_1000},
      {"DICT_ARUCO_ORIGINAL", DICT_ARUCO_ORIGINAL},
      {"DICT_APRILTAG_16h5", DICT_APRILTAG_16h5},
      {"DICT_APRILTAG_25h9", DICT_APRILTAG_25h9},
      {"DICT_APRILTAG_36h10", DICT_APRILTAG_36h10},
      {"DICT_APRILTAG_36h11", DICT_APRILTAG_36h11},
  };
  return table;
}

int dictionarySize(const std::string& name) {
  const auto pos = name.find_last_of('_');
  if (name.rfind("DICT_APRILTAG", 0) == 0) {
    if (name == "DICT_APRILTAG_16h5") return 30;
    if (name == "DICT_APRILTAG_25h9") return 35;
    if (name == "DICT_APRILTAG_36h10") return 2320;
    return 587;
  }
  if (name == "DICT_ARUCO_ORIGINAL") return 1024;
  return std::stoi(name.substr(pos + 1));
}

}  // namespace

MarkerSpec MarkerSpec::parse(const std::string& text) {
  const std::string form = "expected DICT:ID:SIDE_M, for example DICT_6X6_250:23:0.12";
  std::vector<std::string> parts;
  std::stringstream ss(text);
  std::string part;
  while (std::getline(ss, part, ':')) parts.push_back(part);
  if (parts.size() != 3) throw Error("marker '" + text + "': " + form);
  MarkerSpec m;
  m.dictionary = parts[0];
  try {
    size_t used = 0;
    m.id = std::stoi(parts[1], &used);
    if (used != parts[1].size()) throw std::invalid_argument("id");
    m.sideMetres = std::stod(parts[2], &used);
    if (used != parts[2].size()) throw std::invalid_argument("side");
  } catch (const std::exception&) {
    throw Error("marker '" + text + "': " + form);
  }
  m.check();
  return m;
}

std::string MarkerSpec::toString() const {
  std::ostringstream ss;
  ss << dictionary << ':' << id << ':' << sideMetres;
  return ss.str();
}

void MarkerSpec::check() const {
  dictionaryEnum();
  if (id < 0 || id >= dictionarySize(dictionary))
    throw Error("marker id " + std::to_string(id) + " is not in " + dictionary + " (0.." +
                std::to_string(dictionarySize(dictionary) - 1) + ")");
  if (!(std::isfinite(sideMetres) && sideMetres > 0.0))
    throw Error("marker side length must be a positive number of metres");
}

int MarkerSpec::dictionaryEnum() const {
  for (const auto& [name, value] : dictionaries())
    if (name == dictionary) return value;
  std::string known;
  for (const auto& [name, value] : dictionaries()) known += (known.empty() ? "" : ", ") + name;
  throw Error("unknown ArUco dictionary '" + dictionary + "' (known: " + known + ")");
}

std::array<Eigen::Vector3d, 4> MarkerSpec::cornersWorld() const {
  const double h = 0.5 * sideMetres;
  return {Eigen::Vector3d(-h, h, 0), Eigen::Vector3d(h, h, 0), Eigen::Vector3d(h, -h, 0),
          Eigen::Vector3d(-h, -h, 0)};
}

}  // namespace reftrack
