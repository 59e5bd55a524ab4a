#include "engine/config/ReferenceSelectionParams.hpp"

#include "engine/config/FieldDescriber.hpp"
#include "engine/config/ParamFields.hpp"

namespace reftrack {

template <class Self, class Field>
void ReferenceSelectionParams::fields(Self& p, const Field& field) {
  field("angle_weight", p.angleWeight, Range{0.0, 1e6})
      .help(
          "Reference cost: centre distance / scene depth plus this times the viewing angle change "
          "(radians)");
  field("min_shared_points", p.minSharedPoints, Range{6, 1000000})
      .help("Reference pairs sharing fewer map points are never used");
  field("switch_margin", p.switchMargin, Range{0.0, 0.99})
      .help(
          "Switch reference pairs only when another costs this fraction less than the pair in use");
  field("switch_after_frames", p.switchAfterFrames, Range{1, 1000000})
      .help("Consecutive frames another pair must be cheaper before the tracker switches to it");
  field("cached_trackers", p.cachedTrackers, Range{1, 1000})
      .help(
          "Pair trackers kept ready (each holds two prepared images); more: faster switches, more "
          "memory");
  field("reseed_frames", p.reseedFrames, Range{0, 1000000})
      .help("Lost for at most this many frames: retry from the last pose before relocalising");
}

template struct ParamSection<ReferenceSelectionParams>;
template void ReferenceSelectionParams::fields(const ReferenceSelectionParams&,
                                               const FieldDescriber&);

}  // namespace reftrack
