#include "engine/config/CorrelationParams.hpp"

#include "engine/config/FieldDescriber.hpp"
#include "engine/config/ParamFields.hpp"

namespace reftrack {

template <class Self, class Field>
void CorrelationParams::fields(Self& p, const Field& field) {
  field("half_window", p.halfWindow, Range{1, 32})
      .help("n: correlation windows are (2n+1) x (2n+1) pixels; larger: more distinctive, slower");
  field("min_score", p.minScore, Range{-1.0, 1.0})
      .help("A match is kept only above this NCC score; higher: fewer, surer matches");
  field("search_half_width_px", p.searchHalfWidthPx, Range{0.0, 100000.0})
      .help(
          "Frame-to-frame search reach, +-this horizontally (pixels at 320x240, scaled); larger: "
          "faster motion, slower");
  field("search_half_height_px", p.searchHalfHeightPx, Range{0.0, 100000.0})
      .help("Frame-to-frame search reach, +-this vertically (pixels at 320x240, scaled)");
  field("symmetric_check", p.symmetricCheck)
      .help("Keep only mutual best matches (each the other's best candidate)");
}

template struct ParamSection<CorrelationParams>;
template void CorrelationParams::fields(const CorrelationParams&, const FieldDescriber&);

}  // namespace reftrack
