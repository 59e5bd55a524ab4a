#include "app/viewer/SoakMonitor.hpp"

#include <malloc.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <utility>

#include "engine/core/Error.hpp"

namespace reftrack::app {

std::optional<double> residentMemoryMiB() {
  std::ifstream statm("/proc/self/statm");
  long long totalPages = 0, residentPages = 0;
  if (!(statm >> totalPages >> residentPages)) return std::nullopt;
  const long pageBytes = sysconf(_SC_PAGESIZE);
  if (pageBytes <= 0) return std::nullopt;
  return static_cast<double>(residentPages) * static_cast<double>(pageBytes) / (1024.0 * 1024.0);
}

double heapInUseMiB() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd) / (1024.0 * 1024.0);
}

double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double SoakClocks::steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

SoakMonitor::SoakMonitor(int interval, int warmup, std::ostream* out, SoakClocks clocks)
    : interval_(interval), warmup_(warmup), out_(out), clocks_(std::move(clocks)) {
  if (interval < 1) throw Error("soak report interval must be at least 1 frame");
  if (warmup < 0) throw Error("soak warm-up must not be negative");
  if (!clocks_.wallSeconds || !clocks_.cpuSeconds) throw Error("soak monitor: a clock is missing");
  intervalStart_ = clocks_.wallSeconds();
  intervalCpuStart_ = clocks_.cpuSeconds();
}

void SoakMonitor::frameDone() {
  ++frames_;
  if (frames_ % interval_ != 0) return;
  const double now = clocks_.wallSeconds();
  const double seconds = now - intervalStart_;
  intervalStart_ = now;
  const double cpu = clocks_.cpuSeconds();
  const double cpuSeconds = cpu - intervalCpuStart_;
  intervalCpuStart_ = cpu;
  SoakSample s;
  s.frames = frames_;
  s.residentMiB = residentMemoryMiB().value_or(0.0);
  s.heapInUseMiB = heapInUseMiB();
  s.framesPerSecond = seconds > 0 ? interval_ / seconds : 0.0;
  s.cpuMsPerFrame = 1000.0 * cpuSeconds / interval_;
  samples_.push_back(s);
  if (out_) {
    char line[200];
    std::snprintf(
        line, sizeof line,
        "soak: frame %7d  resident %8.1f MiB  heap in use %7.1f MiB  rate %7.1f fr/s  cpu "
        "%7.2f ms/fr%s\n",
        s.frames, s.residentMiB, s.heapInUseMiB, s.framesPerSecond, s.cpuMsPerFrame,
        s.frames <= warmup_ ? "  (warm-up)" : "");
    *out_ << line << std::flush;
  }
}

SoakSummary SoakMonitor::summary() const {
  SoakSummary r;
  r.samples = samples_;
  r.warmupFrames = warmup_;
  // The first interval that lies wholly after the warm-up.
  const auto first = std::find_if(samples_.begin(), samples_.end(), [&](const SoakSample& s) {
    return s.frames - interval_ >= warmup_;
  });
  if (first == samples_.end() || first + 1 == samples_.end()) return r;
  r.complete = true;
  r.residentAfterWarmupMiB = first->residentMiB;
  r.residentEndMiB = samples_.back().residentMiB;
  r.growthMiB = r.residentEndMiB - r.residentAfterWarmupMiB;
  r.heapGrowthMiB = samples_.back().heapInUseMiB - first->heapInUseMiB;
  for (auto it = first; it != samples_.end(); ++it)
    r.peakMiB = std::max(r.peakMiB, it->residentMiB);
  r.firstRate = first->framesPerSecond;
  r.lastRate = samples_.back().framesPerSecond;
  r.rateRatio = r.firstRate > 0 ? r.lastRate / r.firstRate : 0.0;
  r.firstCpuMs = first->cpuMsPerFrame;
  r.lastCpuMs = samples_.back().cpuMsPerFrame;
  r.cpuRatio = r.firstCpuMs > 0 ? r.lastCpuMs / r.firstCpuMs : 0.0;
  return r;
}

void printSoakSummary(std::ostream& out, const SoakSummary& s) {
  if (!s.complete) {
    out << "soak: too few frames after the " << s.warmupFrames
        << "-frame warm-up for a verdict (need two report intervals)\n";
    return;
  }
  char line[400];
  std::snprintf(line, sizeof line,
                "soak: memory after warm-up %.1f MiB, end %.1f MiB (growth %+.2f MiB, peak %.1f "
                "MiB; heap in use %+.2f MiB); rate first %.1f fr/s, last %.1f fr/s (ratio %.3f); "
                "cpu first %.2f ms/fr, "
                "last %.2f ms/fr (ratio %.3f)\n",
                s.residentAfterWarmupMiB, s.residentEndMiB, s.growthMiB, s.peakMiB, s.heapGrowthMiB,
                s.firstRate, s.lastRate, s.rateRatio, s.firstCpuMs, s.lastCpuMs, s.cpuRatio);
  out << line;
}

}  // namespace reftrack::app
