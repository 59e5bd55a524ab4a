#pragma once
// MeasurementReliability: what each source of pose measurements (a map point, a reference corner)
// has shown of its own accuracy. A real map mixes points that measure to a fifth of a pixel with
// points a pixel off in every frame (a corner on an occluding edge or a highlight, a junction that
// looks different from each side, a point the references' given poses triangulated off); the
// corner-variance model cannot tell them apart, their residuals at accepted poses can. Each source
// keeps the mean of its whitened squared residuals; its variance factor is that mean, shrunk toward
// the average source by `priorObservations` observations, divided by the average over every
// observation, so the factors average about 1 and the terms' overall weight against the other
// terms and the motion prior is kept.
#include <cstddef>
#include <vector>

namespace reftrack {

class MeasurementReliability {
 public:
  // `sources` sources; priorObservations <= 0 turns the learning off (every factor 1).
  MeasurementReliability(std::size_t sources, double priorObservations);

  // The multiplier of the source's modelled variance: 1 until kWarmUpObservations observations
  // have been made in all, and for a source index out of range.
  double varianceFactor(std::size_t source) const;
  // One residual of the source at an accepted pose, whitened by its modelled variance (before the
  // factor): squared residual over variance, per image axis. Negative or non-finite values are
  // ignored. (No cap: the tracker's gate already bounds a term's residual, and a source whose
  // residuals come near it is the kind this learns to trust less.)
  void observe(std::size_t source, double whitenedSquared);

  void setPriorObservations(double priorObservations) { prior_ = priorObservations; }
  void clear();  // forgets every observation
  // Sources past the current count start unobserved; those beyond `sources` are forgotten.
  void resize(std::size_t sources);
  long observations() const { return count_; }
  std::size_t sources() const { return sum_.size(); }

  static constexpr long kWarmUpObservations = 50;

 private:
  double prior_;
  std::vector<double> sum_;
  std::vector<int> n_;
  double total_ = 0.0;
  long count_ = 0;
};

}  // namespace reftrack
