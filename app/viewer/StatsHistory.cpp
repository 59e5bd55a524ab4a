#include "app/viewer/StatsHistory.hpp"

#include <limits>

#include "engine/core/Error.hpp"

namespace reftrack::app {

StatsHistory::StatsHistory(std::size_t capacity) : capacity_(capacity) {
  if (capacity_ == 0) throw Error("stats history: capacity must be at least 1");
}

void StatsHistory::add(FrameStats stats) {
  if (frames_.size() >= capacity_) frames_.pop_front();
  frames_.push_back(std::move(stats));
}

double StatsHistory::meanFps() const {
  double total = 0.0;
  int n = 0;
  for (const FrameStats& f : frames_)
    if (f.loopMilliseconds > 0) {
      total += f.loopMilliseconds;
      ++n;
    }
  return n > 0 && total > 0 ? 1000.0 * n / total : 0.0;
}

std::vector<float> StatsHistory::poseSeries(int component) const {
  if (component < 0 || component > 5) throw Error("stats history: pose component must be 0..5");
  std::vector<float> out;
  out.reserve(frames_.size());
  for (const FrameStats& f : frames_)
    out.push_back(f.pose ? static_cast<float>((*f.pose)[component])
                         : std::numeric_limits<float>::quiet_NaN());
  return out;
}

std::vector<float> StatsHistory::inlierSeries() const {
  std::vector<float> out;
  out.reserve(frames_.size());
  for (const FrameStats& f : frames_) out.push_back(static_cast<float>(f.inliers));
  return out;
}

namespace {

std::vector<float> seriesOf(const std::deque<FrameStats>& frames,
                            std::optional<double> FrameStats::*value) {
  std::vector<float> out;
  out.reserve(frames.size());
  for (const FrameStats& f : frames)
    out.push_back(f.*value ? static_cast<float>(*(f.*value))
                           : std::numeric_limits<float>::quiet_NaN());
  return out;
}

}  // namespace

std::vector<float> StatsHistory::predictedErrorSeries() const {
  return seriesOf(frames_, &FrameStats::predictedErrorPx);
}

std::vector<float> StatsHistory::trueErrorSeries() const {
  return seriesOf(frames_, &FrameStats::trueErrorPx);
}

}  // namespace reftrack::app
