#include "engine/config/MapExtensionParams.hpp"

#include "engine/config/ParamFields.hpp"

namespace reftrack {

template <class Self, class Field>
void MapExtensionParams::fields(Self& p, const Field& field) {
  field("max_distance_m", p.maxDistanceMetres, Range{1e-4, 1000.0});
  field("max_angle_deg", p.maxAngleDeg, Range{0.01, 180.0});
  field("min_inliers", p.minInliers, Range{6, 1000000});
  field("max_support_sd_px", p.maxSupportSdPx, Range{1e-4, 100.0});
  field("match_references", p.matchReferences, Range{1, 1000});
  field("min_overlap_points", p.minOverlapPoints, Range{0, 1000000});
  field("max_epipolar_distance_px", p.maxEpipolarDistancePx, Range{0.01, 100.0});
  field("max_reprojection_error_px", p.maxReprojectionErrorPx, Range{0.01, 100.0});
  field("min_new_points", p.minNewPoints, Range{1, 1000000});
  field("max_references", p.maxReferences, Range{2, 100000});
}

template struct ParamSection<MapExtensionParams>;

}  // namespace reftrack
