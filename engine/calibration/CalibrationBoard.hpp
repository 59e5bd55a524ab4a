#pragma once
// CalibrationBoard: the printed target of `reftrack calibrate`. Parsed from
// "chessboard:COLSxROWS:SQUARE_M" (inner corners, square side in metres) or
// "charuco:DICT:SQXxSQY:SQUARE_M:MARKER_M" (squares, square and marker sides in metres).
// Board frame: origin at the first inner corner, x along a row, y down the columns, z = 0.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace reftrack {

struct CalibrationBoard {
  enum class Kind { Chessboard, Charuco };
  Kind kind = Kind::Chessboard;
  int columns = 9;  // chessboard: inner corners per row; charuco: squares along x
  int rows = 6;     // chessboard: inner corners per column; charuco: squares along y
  double squareMetres = 0.025;
  double markerMetres = 0.0;                // charuco only
  std::string dictionary = "DICT_6X6_250";  // charuco only

  // Throws reftrack::Error quoting the expected forms on a malformed string.
  static CalibrationBoard parse(const std::string& text);
  std::string toString() const;
  // Throws reftrack::Error naming the bad field.
  void check() const;

  // Inner-corner grid (columns x rows of corners): chessboard as given, charuco squares - 1.
  cv::Size cornerGrid() const;
  // The 3D position (board frame, metres) of inner corner `index` (row-major over cornerGrid()).
  cv::Point3f cornerPosition(int index) const;
  std::vector<cv::Point3f> allCornerPositions() const;
};

}  // namespace reftrack
