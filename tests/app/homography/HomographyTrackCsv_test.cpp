#include "app/homography/HomographyTrackCsv.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "TestPaths.hpp"

using namespace reftrack::app;

TEST(HomographyTrackCsv, RowsCarryStatusRatioHAndTime) {
  HomographyFrameRecord r;
  r.index = 7;
  r.timestamp = 1305031102.175304;  // a TUM RGB-D timestamp: kept to the microsecond
  r.tracked = true;
  r.inlierRatio = 0.8125;
  r.H = cv::Matx33d(1.01, 0.002, 12.5, -0.003, 0.99, -4.25, 1.5e-5, -2e-6, 1.0);
  r.milliseconds = 1.234;
  const std::string row = homographyCsvRow(r);
  std::stringstream in(row);
  std::vector<std::string> fields;
  for (std::string f; std::getline(in, f, ',');) fields.push_back(f);
  ASSERT_EQ(fields.size(), 14u);
  EXPECT_EQ(fields[0], "7");
  EXPECT_EQ(fields[1], "1305031102.175304");
  EXPECT_EQ(fields[2], "tracked");
  EXPECT_DOUBLE_EQ(std::stod(fields[3]), 0.8125);
  // %.10g: every entry back to 10 significant digits (these are exact at that precision).
  for (int k = 0; k < 9; ++k) EXPECT_DOUBLE_EQ(std::stod(fields[4 + k]), r.H.val[k]) << k;
  EXPECT_DOUBLE_EQ(std::stod(fields[13]), 1.234);
  r.tracked = false;
  EXPECT_NE(homographyCsvRow(r).find(",lost,"), std::string::npos);
  std::stringstream header(homographyCsvHeader());
  int columns = 0;
  for (std::string f; std::getline(header, f, ',');) ++columns;
  EXPECT_EQ(columns, 14);
}

TEST(HomographyTrackCsv, WritesHeaderAndOneLinePerFrame) {
  const auto dir = reftrack::test::freshTempDir("HomographyTrackCsv");
  std::vector<HomographyFrameRecord> records(3);
  for (int k = 0; k < 3; ++k) records[static_cast<size_t>(k)].index = k;
  writeHomographyCsv(dir / "out.csv", records);
  std::ifstream in(dir / "out.csv");
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], homographyCsvHeader());
  EXPECT_EQ(lines[3].substr(0, 16), "2,0.000000,lost,");
  EXPECT_THROW(writeHomographyCsv(dir / "missing" / "x.csv", records), std::exception);
}
