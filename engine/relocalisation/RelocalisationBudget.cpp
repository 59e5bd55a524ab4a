#include "engine/relocalisation/RelocalisationBudget.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/Error.hpp"

namespace reftrack {

RelocalisationBudget::RelocalisationBudget(double msPerFrame, double burstMs, double reserveShare) {
  configure(msPerFrame, burstMs, reserveShare);
}

void RelocalisationBudget::configure(double msPerFrame, double burstMs, double reserveShare) {
  if (!(std::isfinite(msPerFrame) && msPerFrame >= 0.0))
    throw Error("relocalisation budget: " + std::to_string(msPerFrame) +
                " ms per frame is not a finite number >= 0");
  if (!(std::isfinite(burstMs) && burstMs >= 0.0))
    throw Error("relocalisation budget: a burst of " + std::to_string(burstMs) +
                " ms is not a finite number >= 0");
  if (!(reserveShare >= 0.0 && reserveShare < 1.0))
    throw Error("relocalisation budget: a reserve share of " + std::to_string(reserveShare) +
                " of the burst is not in [0, 1)");
  msPerFrame_ = msPerFrame;
  burstMs_ = burstMs;
  reserveMs_ = reserveShare * burstMs;
  bucketMs_ = burstMs;
}

void RelocalisationBudget::refill() { bucketMs_ = std::max(bucketMs_, burstMs_); }

bool RelocalisationBudget::lostFrame() {
  // Due while the bucket holds more than the reserve: with an empty burst the first lost frame
  // still tries (its share makes the bucket positive), then one attempt per cost / msPerFrame
  // frames.
  bucketMs_ = std::min(burstMs_ + msPerFrame_, bucketMs_ + msPerFrame_);
  return bucketMs_ > reserveMs_;
}

void RelocalisationBudget::spent(double ms) {
  if (!(ms > 0.0)) return;
  bucketMs_ -= ms;
  spentMs_ += ms;
}

}  // namespace reftrack
