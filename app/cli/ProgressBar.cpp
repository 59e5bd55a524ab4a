#include "app/cli/ProgressBar.hpp"

#include <unistd.h>

#include <cstdio>

namespace reftrack::app {

namespace {
std::string formatSeconds(double s) {
  if (!(s >= 0) || s > 359999) return "--:--";
  const int total = static_cast<int>(s + 0.5);
  char buf[32];
  if (total >= 3600)
    std::snprintf(buf, sizeof buf, "%d:%02d:%02d", total / 3600, (total / 60) % 60, total % 60);
  else
    std::snprintf(buf, sizeof buf, "%02d:%02d", total / 60, total % 60);
  return buf;
}
}  // namespace

ProgressBar::ProgressBar(std::string label, std::size_t total, std::string unit)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      total_(total),
      interactive_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      lastDraw_(start_) {}

ProgressBar::~ProgressBar() {
  if (!finished_ && interactive_ && done_ > 0) std::fputc('\n', stderr);
}

void ProgressBar::advance(std::size_t n) {
  done_ += n;
  draw(false);
}

void ProgressBar::draw(bool force) {
  if (!interactive_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - lastDraw_ < std::chrono::milliseconds(100) && done_ < total_) return;
  lastDraw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? done_ / elapsed : 0.0;
  const double frac = total_ ? static_cast<double>(done_) / total_ : 1.0;
  const int width = 30, filled = static_cast<int>(frac * width);
  std::string bar(filled, '#');
  bar += std::string(width - filled, '.');
  const double left = rate > 0 ? (total_ - done_) / rate : -1.0;
  std::fprintf(stderr, "\r%s [%s] %zu/%zu %3.0f%% %.1f %s/s %s left ", label_.c_str(), bar.c_str(),
               done_, total_, 100.0 * frac, rate, unit_.c_str(), formatSeconds(left).c_str());
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (finished_) return;
  draw(true);
  finished_ = true;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stderr, "%s%s: %zu %s in %.1f s (%.1f %s/s)\n", interactive_ ? "\n" : "",
               label_.c_str(), done_, unit_.c_str(), elapsed, elapsed > 0 ? done_ / elapsed : 0.0,
               unit_.c_str());
}

}  // namespace reftrack::app
