#include "engine/calibration/CalibrationBoard.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"

using namespace reftrack;

TEST(CalibrationBoard, ParsesChessboardAndCharuco) {
  const CalibrationBoard c = CalibrationBoard::parse("chessboard:9x6:0.025");
  EXPECT_EQ(c.kind, CalibrationBoard::Kind::Chessboard);
  EXPECT_EQ(c.cornerGrid(), cv::Size(9, 6));
  EXPECT_DOUBLE_EQ(c.squareMetres, 0.025);
  EXPECT_EQ(c.allCornerPositions().size(), 54u);
  // Corner 10 is the second corner of the second row: one square right, one square down.
  EXPECT_NEAR(c.cornerPosition(10).x, 0.025, 1e-7);
  EXPECT_NEAR(c.cornerPosition(10).y, 0.025, 1e-7);
  EXPECT_EQ(CalibrationBoard::parse(c.toString()).cornerGrid(), c.cornerGrid());

  const CalibrationBoard h = CalibrationBoard::parse("charuco:DICT_6X6_250:5x7:0.04:0.02");
  EXPECT_EQ(h.kind, CalibrationBoard::Kind::Charuco);
  EXPECT_EQ(h.cornerGrid(), cv::Size(4, 6));  // squares minus one per side
  EXPECT_DOUBLE_EQ(h.markerMetres, 0.02);
  EXPECT_EQ(CalibrationBoard::parse(h.toString()).toString(), h.toString());
}

TEST(CalibrationBoard, RejectsMalformedSpecsNamingTheField) {
  auto message = [](const std::string& spec) {
    try {
      CalibrationBoard::parse(spec);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("circles:4x11:0.02").find("expected chessboard"), std::string::npos);
  EXPECT_NE(message("chessboard:9by6:0.025").find("grid"), std::string::npos);
  EXPECT_NE(message("chessboard:9x6:abc").find("square side"), std::string::npos);
  EXPECT_NE(message("chessboard:9x6:-1").find("square side"), std::string::npos);
  EXPECT_NE(message("chessboard:1x6:0.02").find("at least 2"), std::string::npos);
  EXPECT_NE(message("charuco:DICT_6X6_250:5x7:0.04:0.05").find("marker side"), std::string::npos);
  EXPECT_NE(message("charuco:DICT_NOPE:5x7:0.04:0.02").find("unknown ArUco dictionary"),
            std::string::npos);
  EXPECT_THROW(CalibrationBoard().cornerPosition(54), Error);
}

// Found by tests/fuzz (fuzz_board_string): a huge negative grid size was cast to int (undefined
// behaviour) before the range check.
TEST(CalibrationBoard, HugeNegativeGridIsAnErrorNotACast) {
  EXPECT_THROW(CalibrationBoard::parse("chessboard:-6.7e97x6:0.025"), Error);
  EXPECT_THROW(CalibrationBoard::parse("charuco:DICT_6X6_250:5x-1e300:0.04:0.02"), Error);
}
