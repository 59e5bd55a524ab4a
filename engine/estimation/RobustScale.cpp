#include "engine/estimation/RobustScale.hpp"

#include <algorithm>
#include <cmath>

namespace reftrack {

double robustSd(std::vector<double>& norms, ResidualDimension dimension) {
  if (norms.empty()) return NAN;
  const auto middle = norms.begin() + static_cast<long>(norms.size() / 2);
  std::nth_element(norms.begin(), middle, norms.end());
  const double median = *middle;
  return median / (dimension == ResidualDimension::One ? 0.6744897501960817 : 1.1774100225154747);
}

}  // namespace reftrack
