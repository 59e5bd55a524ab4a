#include "engine/config/RansacParams.hpp"

#include "engine/config/FieldDescriber.hpp"
#include "engine/config/ParamFields.hpp"

namespace reftrack {

template <class Self, class Field>
void RansacParams::fields(Self& p, const Field& field) {
  field("max_iterations", p.maxIterations, Range{1, 1000000})
      .help(
          "Homography RANSAC stops after this many samples; more: more robust to outliers, slower");
  field("early_accept_support", p.earlyAcceptSupport, Range{0.0, 1.0})
      .help("Accept a homography at once when this fraction of the matches supports it");
  field("early_accept_min_iterations", p.earlyAcceptMinIterations, Range{1, 1000000})
      .help("Samples drawn at least before a homography is accepted early");
  field("min_sample_spacing_px", p.minSampleSpacingPx, Range{0.0, 10000.0})
      .help(
          "The 4 points of a sample lie pairwise at least this far apart (pixels at 320x240, "
          "scaled)");
  field("min_determinant", p.minDeterminant, Range{1e-12, 1.0})
      .help("Refuse a homography unless |det(H / h33)| lies in [m, 1/m] (degenerate or folded)");
  field("min_inlier_ratio", p.minInlierRatio, Range{0.0, 1.0})
      .help("A frame fails when fewer than this fraction of its matches are inliers");
  field("min_inliers", p.minInliers, Range{4, 1000000})
      .help("A frame fails with fewer inliers than this");
  field("inlier_threshold_px", p.inlierThresholdPx, Range{1e-6, 1000.0})
      .help(
          "Inlier transfer error (pixels at 320x240, scaled); larger: more tolerant, less precise");
  field("refine", p.refine)
      .help("Refine the homography on its inliers (non-linear, transfer error)");
  field("seed", p.seed, Range{0, 2147483647})
      .help("Random generator seed: the same seed gives the same run");
  field("progressive_sampling", p.progressiveSampling)
      .help(
          "Draw samples from the best-scored matches first (PROSAC); false: uniform, as in the "
          "paper");
}

template struct ParamSection<RansacParams>;
template void RansacParams::fields(const RansacParams&, const FieldDescriber&);

}  // namespace reftrack
