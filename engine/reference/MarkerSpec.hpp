#pragma once
// MarkerSpec: which printed ArUco marker fixes the world frame — dictionary, id and side length
// (metres). Parsed from "DICT_6X6_250:23:0.12". The world frame is the marker's frame as OpenCV
// aruco defines it: origin at the centre, x right, y up on the marker, z out of the marker plane.
#include <Eigen/Core>
#include <array>
#include <string>

namespace reftrack {

struct MarkerSpec {
  std::string dictionary = "DICT_6X6_250";
  int id = 23;
  double sideMetres = 0.12;

  // Throws reftrack::Error with the expected form on a malformed string.
  static MarkerSpec parse(const std::string& text);
  std::string toString() const;
  void check() const;
  // OpenCV's predefined dictionary enum value (cv::aruco::PREDEFINED_DICTIONARY_NAME).
  int dictionaryEnum() const;
  // The four corners in world coordinates, in aruco's order (top-left, top-right,
  // bottom-right, bottom-left as printed).
  std::array<Eigen::Vector3d, 4> cornersWorld() const;
};

}  // namespace reftrack
