#include "engine/calibration/CalibrationBoard.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "engine/core/Error.hpp"
#include "engine/reference/MarkerSpec.hpp"

namespace reftrack {

namespace {

const char* kForms =
    "expected chessboard:COLSxROWS:SQUARE_M (inner corners, e.g. chessboard:9x6:0.025) or "
    "charuco:DICT:SQXxSQY:SQUARE_M:MARKER_M (e.g. charuco:DICT_6X6_250:5x7:0.04:0.02)";

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::stringstream ss(text);
  std::string part;
  while (std::getline(ss, part, sep)) parts.push_back(part);
  if (!text.empty() && text.back() == sep) parts.emplace_back();
  return parts;
}

double parseNumber(const std::string& text, const std::string& board, const char* field) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v))
    throw Error("board '" + board + "': " + field + " '" + text + "' is not a number; " + kForms);
  return v;
}

void parseGrid(const std::string& text, const std::string& board, int& cols, int& rows) {
  const auto x = text.find_first_of("xX");
  if (x == std::string::npos)
    throw Error("board '" + board + "': grid '" + text + "' must look like 9x6; " + kForms);
  const double c = parseNumber(text.substr(0, x), board, "grid columns");
  const double r = parseNumber(text.substr(x + 1), board, "grid rows");
  if (c != std::floor(c) || r != std::floor(r) || c < 0 || r < 0 || c > 1000 || r > 1000)
    throw Error("board '" + board + "': grid '" + text + "' must be two whole numbers");
  cols = static_cast<int>(c);
  rows = static_cast<int>(r);
}

}  // namespace

CalibrationBoard CalibrationBoard::parse(const std::string& text) {
  const std::vector<std::string> parts = split(text, ':');
  CalibrationBoard b;
  if (parts.size() == 3 && parts[0] == "chessboard") {
    b.kind = Kind::Chessboard;
    parseGrid(parts[1], text, b.columns, b.rows);
    b.squareMetres = parseNumber(parts[2], text, "square side");
  } else if (parts.size() == 5 && parts[0] == "charuco") {
    b.kind = Kind::Charuco;
    b.dictionary = parts[1];
    parseGrid(parts[2], text, b.columns, b.rows);
    b.squareMetres = parseNumber(parts[3], text, "square side");
    b.markerMetres = parseNumber(parts[4], text, "marker side");
  } else {
    throw Error("board '" + text + "' not understood; " + kForms);
  }
  try {
    b.check();
  } catch (const Error& e) {
    throw Error("board '" + text + "': " + e.what());
  }
  return b;
}

std::string CalibrationBoard::toString() const {
  std::ostringstream ss;
  if (kind == Kind::Chessboard)
    ss << "chessboard:" << columns << 'x' << rows << ':' << squareMetres;
  else
    ss << "charuco:" << dictionary << ':' << columns << 'x' << rows << ':' << squareMetres << ':'
       << markerMetres;
  return ss.str();
}

void CalibrationBoard::check() const {
  const int minimum = kind == Kind::Chessboard ? 2 : 3;
  if (columns < minimum || rows < minimum)
    throw Error(std::string(kind == Kind::Chessboard ? "inner corners" : "squares") +
                " per side must be at least " + std::to_string(minimum) + ", got " +
                std::to_string(columns) + "x" + std::to_string(rows));
  if (!(squareMetres > 0.0 && std::isfinite(squareMetres)))
    throw Error("square side must be a positive length in metres");
  if (kind == Kind::Charuco) {
    if (!(markerMetres > 0.0 && markerMetres < squareMetres))
      throw Error("marker side must be positive and smaller than the square side");
    MarkerSpec spec;
    spec.dictionary = dictionary;
    spec.id = 0;
    spec.dictionaryEnum();  // throws on an unknown dictionary name
  }
}

cv::Size CalibrationBoard::cornerGrid() const {
  return kind == Kind::Chessboard ? cv::Size(columns, rows) : cv::Size(columns - 1, rows - 1);
}

cv::Point3f CalibrationBoard::cornerPosition(int index) const {
  const cv::Size grid = cornerGrid();
  if (index < 0 || index >= grid.area())
    throw Error("board corner index " + std::to_string(index) + " out of range");
  return {static_cast<float>((index % grid.width) * squareMetres),
          static_cast<float>((index / grid.width) * squareMetres), 0.0f};
}

std::vector<cv::Point3f> CalibrationBoard::allCornerPositions() const {
  std::vector<cv::Point3f> out;
  for (int i = 0; i < cornerGrid().area(); ++i) out.push_back(cornerPosition(i));
  return out;
}

}  // namespace reftrack
