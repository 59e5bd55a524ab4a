#pragma once
// CorrelationParams: NCC over (2n+1)^2 windows and the narrow-baseline search (paper Sec. 6.1,
// Eq. 17). The search window is given at 320x240 and scales with the image.
#include <opencv2/core.hpp>

#include "engine/config/ParamSection.hpp"

namespace reftrack {

struct CorrelationParams : ParamSection<CorrelationParams> {
  static constexpr const char* kSection = "correlation";

  int halfWindow = 5;              // n: windows are (2n+1) x (2n+1) pixels
  double minScore = 0.8;           // keep the best candidate only above this NCC
  double searchHalfWidthPx = 40;   // candidates within +-this horizontally (at 320x240)
  double searchHalfHeightPx = 30;  // and +-this vertically (at 320x240)
  bool symmetricCheck = true;      // keep mutual best pairs only

  int windowSide() const { return 2 * halfWindow + 1; }
  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
};
extern template struct ParamSection<CorrelationParams>;  // defined in CorrelationParams.cpp

}  // namespace reftrack
