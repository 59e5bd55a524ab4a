#include "engine/tracking/MeasurementGroupNoise.hpp"

#include <algorithm>
#include <cmath>

namespace reftrack {

namespace {

// The median of the chi-square distribution with 1 and 2 degrees of freedom: a Gaussian
// residual's whitened squared norm has this median when its variance is modelled right.
constexpr double kChiSquareMedian[3] = {0.0, 0.4549364231195724, 1.3862943611198906};

}  // namespace

int residualDimension(MeasurementGroup group) {
  return group == MeasurementGroup::CornerPoints || group == MeasurementGroup::KeypointPoints ? 2
                                                                                              : 1;
}

double MeasurementGroupNoise::meanAbsoluteFactor() const {
  double logSum = 0.0;
  int n = 0;
  for (int g = 0; g < kMeasurementGroups; ++g)
    if (seen_[static_cast<std::size_t>(g)]) {
      logSum += std::log(absolute_[static_cast<std::size_t>(g)]);
      ++n;
    }
  return n > 0 ? std::exp(logSum / n) : 1.0;
}

double MeasurementGroupNoise::varianceFactor(MeasurementGroup group) const {
  const auto g = static_cast<std::size_t>(group);
  if (frames_ <= 0 || !seen_[g]) return 1.0;
  return absolute_[g] / meanAbsoluteFactor();
}

void MeasurementGroupNoise::observe(FrameResiduals residuals) {
  if (frames_ <= 0) return;
  // An exponential average over about `frames_` frames (its weights sum like a window that long).
  const double keep = std::clamp(1.0 - 1.0 / frames_, 0.0, 1.0);
  for (int g = 0; g < kMeasurementGroups; ++g) {
    std::vector<double>& v = residuals.whitenedSquared[static_cast<std::size_t>(g)];
    v.erase(
        std::remove_if(v.begin(), v.end(), [](double x) { return !(x >= 0) || !std::isfinite(x); }),
        v.end());
    if (static_cast<int>(v.size()) < kMinTerms) continue;
    const auto middle = v.begin() + static_cast<long>(v.size() / 2);
    std::nth_element(v.begin(), middle, v.end());
    const double factor = std::max(
        1e-6, *middle / kChiSquareMedian[residualDimension(static_cast<MeasurementGroup>(g))]);
    const auto i = static_cast<std::size_t>(g);
    absolute_[i] = seen_[i] ? keep * absolute_[i] + (1.0 - keep) * factor : factor;
    seen_[i] = true;
  }
}

void MeasurementGroupNoise::clear() {
  absolute_.fill(1.0);
  seen_.fill(false);
}

}  // namespace reftrack
