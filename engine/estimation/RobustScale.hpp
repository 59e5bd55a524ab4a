#pragma once
// RobustScale: the standard deviation of Gaussian noise estimated from the median of its
// magnitudes, which outliers barely move (a mean square would follow them). For residuals of one
// axis, SD = median |r| / 0.6745 (the normal's median absolute value); for isotropic 2-D residual
// vectors, SD per axis = median |r| / 1.1774 (the Rayleigh distribution's median, sqrt(2 ln 2)).
#include <vector>

namespace reftrack {

enum class ResidualDimension { One = 1, Two = 2 };

// The per-axis SD of the residual magnitudes `norms` (non-negative; the vector is reordered);
// NaN when empty.
double robustSd(std::vector<double>& norms, ResidualDimension dimension);

}  // namespace reftrack
