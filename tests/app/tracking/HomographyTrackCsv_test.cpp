#include "app/tracking/HomographyTrackCsv.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "TestPaths.hpp"

using namespace reftrack::app;

namespace {

// Splits a CSV row on commas outside double quotes, unquoting quoted fields ("" -> ").
std::vector<std::string> csvFields(const std::string& row) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < row.size(); ++i) {
    const char c = row[i];
    if (c == '"' && quoted && i + 1 < row.size() && row[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

}  // namespace

TEST(HomographyTrackCsv, RowsCarryStatusRatioHAndTime) {
  HomographyFrameRecord r;
  r.index = 7;
  r.timestamp = 1305031102.175304;  // a TUM RGB-D timestamp: kept to the microsecond
  r.tracked = true;
  r.inlierRatio = 0.8125;
  r.H = cv::Matx33d(1.01, 0.002, 12.5, -0.003, 0.99, -4.25, 1.5e-5, -2e-6, 1.0);
  r.milliseconds = 1.234;
  r.reason = "left over from an earlier frame";  // a tracked frame has no reason
  const std::vector<std::string> fields = csvFields(homographyCsvRow(r));
  ASSERT_EQ(fields.size(), 15u);
  EXPECT_EQ(fields[0], "7");
  EXPECT_EQ(fields[1], "1305031102.175304");
  EXPECT_EQ(fields[2], "tracked");
  EXPECT_DOUBLE_EQ(std::stod(fields[3]), 0.8125);
  // %.10g: every entry back to 10 significant digits (these are exact at that precision).
  for (int k = 0; k < 9; ++k) EXPECT_DOUBLE_EQ(std::stod(fields[4 + k]), r.H.val[k]) << k;
  EXPECT_DOUBLE_EQ(std::stod(fields[13]), 1.234);
  EXPECT_EQ(fields[14], "");
  std::stringstream header(homographyCsvHeader());
  std::vector<std::string> columns;
  for (std::string f; std::getline(header, f, ',');) columns.push_back(f);
  ASSERT_EQ(columns.size(), 15u);
  EXPECT_EQ(columns[14], "reason");
}

TEST(HomographyTrackCsv, LostRowsCarryTheirReasonQuoted) {
  HomographyFrameRecord r;
  r.index = 3;
  r.timestamp = 0.1;
  r.reason = "cold: keypoints: only 2 keypoint matches; unguided: \"too few\" matches (3)";
  const std::string row = homographyCsvRow(r);
  EXPECT_EQ(row.substr(0, 15), "3,0.100000,lost");
  const std::vector<std::string> fields = csvFields(row);
  ASSERT_EQ(fields.size(), 15u) << row;  // the commas and quotes inside stay in one field
  EXPECT_EQ(fields[14], r.reason);
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
