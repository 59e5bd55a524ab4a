#include "engine/core/DataLines.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

using namespace reftrack;

// Blank lines, white space alone and comments (also indented, also with a carriage return) are
// passed over; data lines keep their text and their 1-based number in the file.
TEST(DataLines, VisitsDataLinesWithTheirNumbers) {
  std::istringstream in("# header\n1 a\n\n   \t\r\n  # indented comment\n2 b\r\n3 c");
  std::vector<std::pair<std::string, int>> seen;
  forEachDataLine(in,
                  [&](const std::string& line, int lineNo) { seen.emplace_back(line, lineNo); });
  const std::vector<std::pair<std::string, int>> expected = {{"1 a", 2}, {"2 b\r", 6}, {"3 c", 7}};
  EXPECT_EQ(seen, expected);
}

TEST(DataLines, AnEmptyStreamVisitsNothingAndAThrowStopsTheReading) {
  std::istringstream empty("");
  int calls = 0;
  forEachDataLine(empty, [&](const std::string&, int) { ++calls; });
  EXPECT_EQ(calls, 0);
  std::istringstream in("x\ny\n");
  EXPECT_THROW(forEachDataLine(in,
                               [&](const std::string& line, int) {
                                 ++calls;
                                 if (line == "x") throw std::runtime_error("bad line");
                               }),
               std::runtime_error);
  EXPECT_EQ(calls, 1);
}
