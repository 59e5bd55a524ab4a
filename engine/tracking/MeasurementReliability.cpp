#include "engine/tracking/MeasurementReliability.hpp"

#include <cmath>

namespace reftrack {

MeasurementReliability::MeasurementReliability(std::size_t sources, double priorObservations)
    : prior_(priorObservations), sum_(sources, 0.0), n_(sources, 0) {}

double MeasurementReliability::varianceFactor(std::size_t source) const {
  if (prior_ <= 0.0 || count_ < kWarmUpObservations || source >= sum_.size()) return 1.0;
  const double average = total_ / static_cast<double>(count_);
  if (!(average > 0.0)) return 1.0;
  return (prior_ * average + sum_[source]) / ((prior_ + n_[source]) * average);
}

void MeasurementReliability::observe(std::size_t source, double whitenedSquared) {
  if (source >= sum_.size() || !std::isfinite(whitenedSquared) || whitenedSquared < 0.0) return;
  sum_[source] += whitenedSquared;
  ++n_[source];
  total_ += whitenedSquared;
  ++count_;
}

void MeasurementReliability::resize(std::size_t sources) {
  for (std::size_t i = sources; i < sum_.size(); ++i) {
    total_ -= sum_[i];
    count_ -= n_[i];
  }
  sum_.resize(sources, 0.0);
  n_.resize(sources, 0);
}

void MeasurementReliability::clear() {
  sum_.assign(sum_.size(), 0.0);
  n_.assign(n_.size(), 0);
  total_ = 0.0;
  count_ = 0;
}

}  // namespace reftrack
