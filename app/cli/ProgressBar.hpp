#pragma once
// ProgressBar: "label [#####.....] 120/300 40% 57.3 fr/s 00:03 left" on stderr, redrawn in
// place at most ~10 times a second. Silent when stderr is not a terminal (CI, pipes, tests),
// except for one summary line at the end.
#include <chrono>
#include <cstddef>
#include <string>

namespace reftrack::app {

class ProgressBar {
 public:
  ProgressBar(std::string label, std::size_t total, std::string unit = "fr");
  ~ProgressBar();
  void advance(std::size_t n = 1);
  void finish();  // prints the summary line (count, time, rate)

 private:
  void draw(bool force);
  std::string label_, unit_;
  std::size_t total_, done_ = 0;
  bool interactive_, finished_ = false;
  std::chrono::steady_clock::time_point start_, lastDraw_;
};

}  // namespace reftrack::app
