#include "engine/config/MapExtensionParams.hpp"

#include "engine/config/FieldDescriber.hpp"
#include "engine/config/ParamFields.hpp"

namespace reftrack {

template <class Self, class Field>
void MapExtensionParams::fields(Self& p, const Field& field) {
  field("max_distance_m", p.maxDistanceMetres, Range{1e-4, 1000.0})
      .help(
          "A tracked frame farther than this from every reference camera becomes a reference "
          "(metres)");
  field("max_angle_deg", p.maxAngleDeg, Range{0.01, 180.0})
      .help(
          "A tracked frame turned more than this from the references near it becomes one "
          "(degrees)");
  field("min_inliers", p.minInliers, Range{6, 1000000})
      .help("A new reference needs a tracked pose with at least this many inliers");
  field("max_support_sd_px", p.maxSupportSdPx, Range{1e-4, 100.0})
      .help(
          "A new reference needs a tracked pose whose support SD is at most this (pixels at "
          "320x240)");
  field("match_references", p.matchReferences, Range{1, 1000})
      .help("A new reference is matched to at most this many existing references");
  field("min_overlap_points", p.minOverlapPoints, Range{0, 1000000})
      .help(
          "An existing reference is matched to a new one only with this many map points in its "
          "view");
  field("max_epipolar_distance_px", p.maxEpipolarDistancePx, Range{0.01, 100.0})
      .help("Epipolar gate of that matching (pixels of the image)");
  field("max_reprojection_error_px", p.maxReprojectionErrorPx, Range{0.01, 100.0})
      .help("Reprojection gate of that matching (pixels of the image)");
  field("min_new_points", p.minNewPoints, Range{1, 1000000})
      .help("A frame whose matching gives fewer map points than this is not added");
  field("max_references", p.maxReferences, Range{2, 100000})
      .help("No references are added beyond this many");
}

template struct ParamSection<MapExtensionParams>;
template void MapExtensionParams::fields(const MapExtensionParams&, const FieldDescriber&);

}  // namespace reftrack
