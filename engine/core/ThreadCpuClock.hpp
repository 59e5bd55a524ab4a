#pragma once
// CPU time consumed by the calling thread (clock_gettime(CLOCK_THREAD_CPUTIME_ID)), for costs
// that must not count the time other processes take the core away: wall time under a shared
// machine's load overstates what an attempt needs on one core.
#include <ctime>

namespace reftrack {

// Milliseconds of CPU time the calling thread has used so far (POSIX; 0 where unavailable).
inline double threadCpuMs() {
  timespec t{};
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t) != 0) return 0.0;
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

// Milliseconds of CPU time the whole process has used so far, every thread (OpenCV's workers
// too): what a budget of "a share of one core" must count (POSIX; 0 where unavailable).
inline double processCpuMs() {
  timespec t{};
  if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t) != 0) return 0.0;
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

}  // namespace reftrack
