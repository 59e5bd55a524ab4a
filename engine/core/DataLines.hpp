#pragma once
// forEachDataLine: the data lines of a line-oriented text file (trajectories, frame lists, CSV):
// every line that is neither blank nor a comment ('#' after leading white space), passed with its
// 1-based line number, for error messages that name the line.
#include <functional>
#include <istream>
#include <string>

namespace reftrack {

inline void forEachDataLine(std::istream& in,
                            const std::function<void(const std::string& line, int lineNo)>& visit) {
  std::string line;
  for (int lineNo = 1; std::getline(in, line); ++lineNo) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    visit(line, lineNo);
  }
}

}  // namespace reftrack
