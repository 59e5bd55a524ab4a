#include "engine/config/ReferenceSelectionParams.hpp"

#include "engine/config/ParamFields.hpp"

namespace reftrack {

template <class Self, class Field>
void ReferenceSelectionParams::fields(Self& p, const Field& field) {
  field("angle_weight", p.angleWeight, Range{0.0, 1e6});
  field("min_shared_points", p.minSharedPoints, Range{6, 1000000});
  field("switch_margin", p.switchMargin, Range{0.0, 0.99});
  field("switch_after_frames", p.switchAfterFrames, Range{1, 1000000});
  field("cached_trackers", p.cachedTrackers, Range{1, 1000});
  field("reseed_frames", p.reseedFrames, Range{0, 1000000});
}

template struct ParamSection<ReferenceSelectionParams>;

}  // namespace reftrack
