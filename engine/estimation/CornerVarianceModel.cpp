#include "engine/estimation/CornerVarianceModel.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "engine/core/Error.hpp"

namespace reftrack {

double CornerVarianceModel::variance(double rmsContrast) const {
  const double c = std::max(minContrast, std::isfinite(rmsContrast) ? rmsContrast : minContrast);
  return floorPx2 + scalePx2 / (c * c);
}

double CornerVarianceModel::sigma(double rmsContrast) const {
  return std::sqrt(variance(rmsContrast));
}

void CornerVarianceModel::check() const {
  if (!std::isfinite(floorPx2) || floorPx2 <= 0)
    throw Error("corner_variance.floor_px2 must be a positive number");
  if (!std::isfinite(scalePx2) || scalePx2 < 0)
    throw Error("corner_variance.scale_px2 must be a non-negative number");
  if (!std::isfinite(minContrast) || minContrast <= 0)
    throw Error("corner_variance.min_contrast must be a positive number");
}

CornerVarianceModel CornerVarianceModel::fit(const std::vector<double>& contrast,
                                             const std::vector<double>& variance) {
  if (contrast.size() != variance.size() || contrast.size() < 2)
    throw Error("CornerVarianceModel::fit needs at least two (contrast, variance) pairs");
  // Relative least squares (each point weighted by 1/variance) so the low-variance plateau is
  // fitted as well as the steep low-contrast end.
  Eigen::MatrixXd A(contrast.size(), 2);
  Eigen::VectorXd b(contrast.size());
  for (std::size_t i = 0; i < contrast.size(); ++i) {
    const double w = 1.0 / std::max(variance[i], 1e-12);
    A(static_cast<Eigen::Index>(i), 0) = w;
    A(static_cast<Eigen::Index>(i), 1) = w / (contrast[i] * contrast[i]);
    b(static_cast<Eigen::Index>(i)) = 1.0;
  }
  const Eigen::Vector2d x = A.colPivHouseholderQr().solve(b);
  CornerVarianceModel m;
  m.floorPx2 = std::max(x(0), 1e-6);
  m.scalePx2 = std::max(x(1), 0.0);
  return m;
}

}  // namespace reftrack
