#include "engine/config/CorrelationParams.hpp"

#include "engine/config/ParamFields.hpp"

namespace reftrack {

template <class Self, class Field>
void CorrelationParams::fields(Self& p, const Field& field) {
  field("half_window", p.halfWindow, Range{1, 32});
  field("min_score", p.minScore, Range{-1.0, 1.0});
  field("search_half_width_px", p.searchHalfWidthPx, Range{0.0, 100000.0});
  field("search_half_height_px", p.searchHalfHeightPx, Range{0.0, 100000.0});
  field("symmetric_check", p.symmetricCheck);
}

template struct ParamSection<CorrelationParams>;

}  // namespace reftrack
