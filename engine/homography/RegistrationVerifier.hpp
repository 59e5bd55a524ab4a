#pragma once
// RegistrationVerifier: the last check of a cold registration (issue 26) — is the reference,
// warped by H, where the frame shows it? Independent of how H was found: textured reference
// points that H maps into the frame (the most textured one per cell of a grid over the frame),
// each reference window,
// warped by H's local affine map (Eq. 19), is correlated (NCC) with the frame within a search
// radius of its mapped position, and a homography correction C (mapped position -> correlation
// peak) is fitted to the peaks robustly. The comparison runs at pyramid levels where the
// reference and the frame have about the same scale (a frame zoomed 4x in: its level 2; zoomed
// out: a reference level), so sharp and blurred copies of the texture are not compared. H passes
// when enough of the points the frame can measure agree with C (confirm), the confirming points
// spread over the part of the frame that sees the reference (a homography right in one corner and
// off elsewhere is refused), and C moves no point of the textured part of the overlap by much: C
// measures how far off H is there, up to the search radius. Given the region H is known to
// explain (SupportRegion: the hull of its inlier matches), only that region is compared — on a
// view that is only partly the plane, trees, people, sky and other facades do not refuse a
// correct H — and the region must hold minSupportFraction of the overlap. Measured on the real
// and hard pairs (`experiment-homography --experiment verify`): the true homographies pass (but
// those of the windblown trees and the most blurred bikes pair, which the images contradict by 6-17
// px), and none moved by 10 or 20 px at the frame corners passes, 71 of 180 moved by 5 px, 162 by 3
// px.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "engine/config/HomographyTrackerParams.hpp"
#include "engine/features/ImagePyramid.hpp"
#include "engine/homography/SupportRegion.hpp"

namespace reftrack {

// Distances are pixels at 320x240 on the compared levels (scaled with the level's size).
struct RegistrationCheckParams {
  int halfWindow = 5;                  // correlation windows (2n+1)^2 pixels, on the levels
  double minScore = 0.5;               // a peak below this NCC is not used
  double searchRadiusAt320 = 4.0;      // peaks are searched within +- this of the mapped position
  double confirmToleranceAt320 = 1.0;  // C's inlier distance: a point within it confirms
  double minConfirmedFraction = 0.3;   // of the measurable points
  int minConfirmed = 8;
  double minSpread = 0.5;       // confirmed cells / measurable cells of a 3x3 grid over the overlap
  double maxOffsetAt320 = 2.0;  // C may move the confirmed overlap by at most this
  // With a support region: it must hold at least this fraction of the overlap (a homography
  // explaining a small patch only is not a registration of the view).
  double minSupportFraction = 0.15;
  void check() const;  // throws reftrack::Error naming the bad field
  // The homography parameters' verify_* values.
  static RegistrationCheckParams from(const HomographyTrackerParams& p);
};

struct RegistrationCheck {
  bool passed = false;
  int measurable = 0;     // reference points mapped inside the frame with their window
  int confirmed = 0;      // of those, the ones whose correlation peak confirms H
  double spread = 0.0;    // confirmed / measurable cells of the 3x3 grid over the overlap
  double offsetPx = 0.0;  // C's largest displacement over the textured part of the overlap
                          // (full-resolution frame pixels): how far off H is there
  int frameLevel = 0, referenceLevel = 0;  // the pyramid levels compared
  bool confirmedTooFew = false;  // failed for too few confirming points (not spread or offset)
  // The fraction of the overlap (frame pixels that see the reference through H) inside the
  // support region; 1 when the whole overlap was compared.
  double supportFraction = 1.0;
  bool wholeOverlap = true;  // no support region given: the whole overlap compared
  std::string failure;       // why it did not pass
  // What was compared and found, e.g. "25 of 37 textured points confirm H in the inliers' region
  // (48% of the overlap), off by up to 1.2 px".
  std::string summary() const;
};

class RegistrationVerifier {
 public:
  // reference: 8-bit grey or BGR (converted). Throws reftrack::Error on an empty reference or
  // bad params.
  explicit RegistrationVerifier(const cv::Mat& reference, RegistrationCheckParams params = {});

  // H: reference -> frame (full-resolution pixels). support: the part of the frame H is known to
  // explain (the hull of its inlier matches, full-resolution frame pixels): only the reference
  // points H maps inside it are compared, and it must hold minSupportFraction of the overlap.
  // Default: the whole overlap.
  RegistrationCheck check(const ImagePyramid& frame, const cv::Matx33d& H,
                          const SupportRegion& support = {}) const;

  // The candidate points of reference level `level` (level pixels).
  const std::vector<cv::Point2f>& points(int level) const;
  int levels() const { return static_cast<int>(levels_.size()); }

 private:
  RegistrationCheck checkOnLevels(const ImagePyramid& frame, const cv::Matx33d& H, int frameLevel,
                                  int referenceLevel, const SupportRegion& support) const;
  struct Level {
    cv::Mat image;
    std::vector<cv::Point2f> points;  // candidates (the most textured pixel per block)
    std::vector<float> texture;       // their minimum eigenvalue
  };
  RegistrationCheckParams params_;
  std::vector<Level> levels_;  // the reference and its cv::pyrDown levels
};

}  // namespace reftrack
