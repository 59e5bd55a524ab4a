#pragma once
// SoakMonitor: resident memory and frame rate of a long viewer run, sampled every `interval`
// frames (`reftrack view --report-every N`). After `warmup` frames it measures the memory growth
// and compares the rate of the last interval with the first one after warm-up.
#include <cstddef>
#include <functional>
#include <optional>
#include <ostream>
#include <vector>

namespace reftrack::app {

// Resident set size of this process in MiB (Linux /proc/self/statm); nullopt where unavailable.
std::optional<double> residentMemoryMiB();
// Bytes the C heap holds for live allocations (glibc mallinfo2: in-use chunks of every arena plus
// mmapped blocks), in MiB: unlike the resident size, unaffected by freed memory the allocator
// keeps.
double heapInUseMiB();
// CPU time used by this process so far (all threads), in seconds.
double processCpuSeconds();

struct SoakSample {
  int frames = 0;              // frames processed when sampled
  double residentMiB = 0;      // resident memory then
  double heapInUseMiB = 0;     // live C-heap allocations then (see heapInUseMiB())
  double framesPerSecond = 0;  // rate over the interval that ended here (wall clock)
  double cpuMsPerFrame = 0;    // process CPU time per frame over that interval (all threads):
                               // unlike the rate, unaffected by other processes' load
};

struct SoakSummary {
  std::vector<SoakSample> samples;
  int warmupFrames = 0;
  // Resident memory at the first sample at or after warm-up, and at the last; growth = end - that.
  double residentAfterWarmupMiB = 0, residentEndMiB = 0, growthMiB = 0, peakMiB = 0;
  double heapGrowthMiB = 0;  // live C-heap allocations, end - first sample after warm-up
  // Rate of the first interval after warm-up and of the last interval; ratio = last / first.
  double firstRate = 0, lastRate = 0, rateRatio = 0;
  double firstCpuMs = 0, lastCpuMs = 0, cpuRatio = 0;  // the same for CPU ms per frame
  bool complete = false;  // at least two samples after warm-up (otherwise the figures are unset)
};

// The clocks a SoakMonitor reads, in seconds: wall (steady) time and the process's CPU time by
// default; a test gives its own to check the figures exactly.
struct SoakClocks {
  std::function<double()> wallSeconds = steadySeconds;
  std::function<double()> cpuSeconds = processCpuSeconds;
  static double steadySeconds();
};

class SoakMonitor {
 public:
  // Prints one line per sample to `out` (nullptr: silent). Throws reftrack::Error for
  // interval < 1 or warmup < 0.
  SoakMonitor(int interval, int warmup, std::ostream* out, SoakClocks clocks = {});
  void frameDone();  // call once per processed frame
  SoakSummary summary() const;

 private:
  int interval_, warmup_;
  std::ostream* out_;
  SoakClocks clocks_;
  int frames_ = 0;
  double intervalStart_ = 0, intervalCpuStart_ = 0;
  std::vector<SoakSample> samples_;
};

// "soak: memory after warm-up 212.4 MiB, end 212.9 MiB (growth +0.5 MiB, peak 213.0); rate
// first 41.2 fr/s, last 40.7 fr/s (ratio 0.99)".
void printSoakSummary(std::ostream& out, const SoakSummary& s);

}  // namespace reftrack::app
