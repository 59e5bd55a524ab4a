#pragma once
// RecoveryCostCalibration: measures the recovery's cost model (engine/relocalisation/RecoveryWork)
// against CPU time. A map's frames are played in orders where every frame is recovered (cold
// starts: reset before each frame; a shuffled sequence: every frame a jump from the last), with a
// budget no recovery comes near; each recovery's work, counted, and its process CPU time are the
// samples (the caller runs one OpenCV thread: cv::setNumThreads(1)). The fit is the
// non-negative least-squares one of the model's coefficients to the samples.
#include <cstdio>
#include <string>
#include <vector>

#include "engine/config/TrackerParams.hpp"
#include "engine/reference/MultiReferenceMap.hpp"
#include "engine/relocalisation/RecoveryWork.hpp"

namespace reftrack::app {

struct RecoverySample {
  std::string order;  // "cold" or "shuffled"
  int frame = 0;      // index into the frames
  RecoveryWork work;
  double cpuMs = 0.0;  // measured
  int clip = 0;        // which map and frames it came from (the caller's numbering)
};

// Every frame of `frames` (BGR or grey, the map's size) once cold and once in a shuffled order
// (std::mt19937 seeded by `seed`); only frames a recovery ran on give a sample. Both orders are
// played `repeats` times: the work is the same every time (it is counted, not timed), and each
// recovery keeps the least CPU time measured, the one least inflated by other work (on a shared
// virtual machine, time taken by others is partly counted as this process's CPU time).
std::vector<RecoverySample> collectRecoverySamples(const MultiReferenceMap& map,
                                                   const std::vector<cv::Mat>& frames,
                                                   TrackerParams params, unsigned seed,
                                                   int repeats = 1);

// The non-negative least-squares coefficients of the relative error (each recovery's residual
// over its measured cost, so cheap and dear recoveries weigh alike; every subset of the six terms
// solved, the best non-negative one kept). Throws reftrack::Error without samples.
RecoveryCostModel fitRecoveryCostModel(const std::vector<RecoverySample>& samples);

// How a model's cost compares with the measured one over samples: the sums' ratio (what a budget
// spends in the long run) and the per-sample ratio's median, 10th and 90th percentiles.
struct CostModelAgreement {
  int samples = 0;
  double modelledSumMs = 0.0, measuredSumMs = 0.0;
  double sumRatio = 0.0;  // modelled / measured
  double medianRatio = 0.0, p10Ratio = 0.0, p90Ratio = 0.0;
};
CostModelAgreement agreement(const RecoveryCostModel& model,
                             const std::vector<RecoverySample>& samples);

// The fit and the given (current) model side by side, per order and in all, and the fitted
// coefficients as RecoveryCostModel::defaults would hold them.
void printRecoveryCostCalibration(const RecoveryCostModel& current, const RecoveryCostModel& fitted,
                                  const std::vector<RecoverySample>& samples, std::FILE* out);

}  // namespace reftrack::app
