#include "engine/homography/KeypointHomographyRegistrar.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/relocalisation/KeypointFeatures.hpp"

namespace reftrack {

namespace {

const HomographyTrackerParams& checked(const HomographyTrackerParams& p, const RansacParams& r) {
  p.check();
  r.check();
  if (p.keypoints == KeypointLayer::None)
    throw Error("keypoint registrar: homography.keypoints is 'none'");
  return p;
}

cv::Ptr<cv::Feature2D> makeDetector(const HomographyTrackerParams& p) {
  switch (p.keypoints) {
    case KeypointLayer::Orb:
      return cv::ORB::create(p.keypointFeatures);
    case KeypointLayer::Akaze:
      return cv::AKAZE::create();
    case KeypointLayer::Sift:
      return cv::SIFT::create(p.keypointFeatures);
    case KeypointLayer::None:
      break;
  }
  throw Error("keypoint registrar: no detector for homography.keypoints 'none'");
}

// RANSAC iterations and confidence of the keypoint homography (cv::findHomography): enough for a
// 10% inlier fraction at 99.5% confidence (log(0.005) / log(1 - 0.1^4) ~ 53000 is the worst
// case; OpenCV stops as soon as the inlier fraction found allows).
constexpr int kRansacIterations = 5000;
constexpr double kRansacConfidence = 0.995;

// The iterations that draw, at kRansacConfidence, one all-inlier sample of 4 from `matches`
// matches of which only `minInliers` are inliers (4 of them drawn without replacement): a
// homography with fewer inliers is refused anyway, so a small match set need not be drawn
// kRansacIterations times. OpenCV stops by the best inlier count found so far, which on a
// view that fails (5 inliers of 19) still means ~1100 draws: a frame that registers nowhere
// (BruggeSquare, 11 views) spent 60 ms in RANSAC on sets of 9-23 matches.
int ransacIterations(int matches, int minInliers) {
  double allInliers = 1.0;  // C(minInliers, 4) / C(matches, 4)
  for (int i = 0; i < 4; ++i)
    allInliers *= static_cast<double>(minInliers - i) / static_cast<double>(matches - i);
  if (allInliers >= 1.0) return 1;
  if (allInliers <= 0.0) return kRansacIterations;
  const double n = std::log(1.0 - kRansacConfidence) / std::log1p(-allInliers);
  return static_cast<int>(std::clamp(std::ceil(n), 1.0, static_cast<double>(kRansacIterations)));
}

// The synthetic tilted views' out-of-plane angle (ASIFT samples tilts sqrt(2) and 2, i.e. 45 and
// 60 degrees; one tilt between them covers the 40-55 degree views plain ORB misses).
constexpr double kTiltDeg = 50.0;
// ORB only: a zoomed-in view (the frame shows part of the reference magnified 2.5-4x, like the
// Oxford boat/bark pairs) puts the frame's finest keypoints below the reference's finest ORB
// scale, and the frame's coarse levels, where they would meet, hold few keypoints. The reference
// is detected once more with this many finer (upsampled, 1.2x each: 2.1x) pyramid levels, its
// keypoint count raised so its own levels keep theirs; that view is tried last. Measured on
// img1 of bikes, leuven, trees, ubc and the box photo zoomed 1.4-3.6x with rotation: misses
// at 3.0x and 3.6x where SIFT registers (README, homography cold registration).
constexpr int kZoomFinerLevels = 4;
// ORB only, the last resort when no view gives a homography: a frame zoomed in 5-7x on a small
// part of the reference (ExtremeZoom of real-photo-pairs, 6.2x: a 176x116-pixel patch of the
// 1090x722 working reference) finds few of the reference's keypoints where it looks: the 1000
// strongest over the whole reference leave ~25 there. The reference is detected once more with
// kDenseFeaturesFactor times the keypoints, and the frame at kDenseFrameScale of its working
// scale (the 6x zoom then lies within ORB's 8 levels of 1.2, 3.6x). Measured on ExtremeZoom
// (a prototype with OpenCV's brute-force matcher, mutual ratio-tested matches and RANSAC; inliers
// / the keypoint H's mean error over the overlap): 1000 reference keypoints 5 / 630 px, 4000: 6
// / 516 px, 10000: 10 / 21 px, 20000: 24 / 11 px (the frame at its working scale: 6 inliers; at a
// quarter of it 17). Here: 21 inliers, registered 1.9 px from the given H after the alignment.
constexpr int kDenseFeaturesFactor = 20;
constexpr double kDenseFrameScale = 0.5;
// Frame rows of the descriptor distances held at once by a pass that does not keep them (8 rows
// of a 20000-keypoint view fit in the L2 cache: ExtremeZoom matched in 68 ms, 86 with 256 rows).
constexpr int kDistanceBlockRows = 8;
// The keypoint homography's area ratio (frame pixels per reference pixel, where its inliers lie)
// must lie within [1 / kMaxAreaRatio, kMaxAreaRatio]: zooms to 8x (ExtremeZoom's 6.2x has 38, a
// 4x zoom seen at 40 degrees ~21; the tracker's min_determinant bound of 20 refused such views
// outright).
constexpr double kMaxAreaRatio = 64.0;
// The ratio test's rival: the nearest of the kNearest reference keypoints lying farther than
// max(kDuplicateMinPx, kDuplicateSizeFraction * the keypoint's size) from the nearest.
constexpr int kNearest = 4;
constexpr float kDuplicateMinPx = 4.0f, kDuplicateSizeFraction = 0.25f;
constexpr double kPi = 3.14159265358979323846;

// Keypoints are detected on images brought to between kMinDetectPixels and kMaxDetectPixels
// (same aspect): a small image (a 329x278 photo) is upsampled, so ORB's 31-pixel border and
// patch leave it texture to describe; a large one (1712x1368) is reduced, so the same number of
// strongest keypoints covers it as densely as a 1000x700 image and the two images of a pair keep
// detecting the same texture. Images of 400x300 to 1024x768 pixels (all eight Oxford sets) are
// detected as they are. Measured on the eight Oxford sets resampled to x0.35 (280-350 pixels
// wide, `experiment-homography --experiment pairs --scales 0.35`): within 5 px over the overlap,
// 36/40 detected as they are, 37/40 upsampled to 640x480, 38/40 to 400x300 (a stronger upsampling
// made a 3.2x zoom of a 480x321 photo land 15 px off: KeypointHomographyRegistrar_test).
constexpr double kMinDetectPixels = 400.0 * 300.0;
constexpr double kMaxDetectPixels = 1024.0 * 768.0;
constexpr double kMaxUpsampling = 2.5;

double workingScale(cv::Size size) {
  const double area = static_cast<double>(size.area());
  if (area < kMinDetectPixels) return std::min(kMaxUpsampling, std::sqrt(kMinDetectPixels / area));
  if (area > kMaxDetectPixels) return std::sqrt(kMaxDetectPixels / area);
  return 1.0;
}

// `gray` resampled by `scale` (reduced by area, enlarged linearly; itself at 1).
cv::Mat resampled(const cv::Mat& gray, double scale) {
  if (scale == 1.0) return gray;
  cv::Mat image;
  cv::resize(gray, image, cv::Size(), scale, scale,
             scale < 1.0 ? cv::INTER_AREA : cv::INTER_LINEAR);
  return image;
}

// Keypoints found on an image resampled by `scale`, brought back to the original's pixels
// (pixel centres: x = (x_scaled + 0.5) / scale - 0.5).
void toOriginalPixels(std::vector<cv::KeyPoint>& keypoints, double scale) {
  if (scale == 1.0) return;
  for (cv::KeyPoint& k : keypoints) {
    k.pt.x = static_cast<float>((k.pt.x + 0.5) / scale - 0.5);
    k.pt.y = static_cast<float>((k.pt.y + 0.5) / scale - 0.5);
    k.size = static_cast<float>(k.size / scale);
  }
}

// All the keypoints `detector` finds in `gray` resampled by `scale`, and their descriptors;
// positions and sizes in `gray`'s pixels.
void detectAtScale(cv::Feature2D& detector, const cv::Mat& gray, double scale,
                   std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors) {
  detector.detectAndCompute(resampled(gray, scale), cv::noArray(), keypoints, descriptors);
  toOriginalPixels(keypoints, scale);
}

// The affine map of the reference into a view tilted by tiltDeg across direction `angle`
// (radians): rotate by -angle, compress x by cos(tilt), rotate back, then shift into a canvas
// holding the whole image (its size in `canvas`).
cv::Matx23d tiltMap(cv::Size size, double tiltDeg, double angle, cv::Size& canvas) {
  const double c = std::cos(angle), s = std::sin(angle), t = std::cos(tiltDeg * kPi / 180.0);
  const cv::Matx22d R(c, -s, s, c);
  const cv::Matx22d A = R * cv::Matx22d(t, 0, 0, 1) * R.t();
  double minX = 1e30, minY = 1e30, maxX = -1e30, maxY = -1e30;
  for (const cv::Vec2d& p :
       {cv::Vec2d(0, 0), cv::Vec2d(size.width - 1, 0), cv::Vec2d(0, size.height - 1),
        cv::Vec2d(size.width - 1, size.height - 1)}) {
    const cv::Vec2d q = A * p;
    minX = std::min(minX, q[0]);
    minY = std::min(minY, q[1]);
    maxX = std::max(maxX, q[0]);
    maxY = std::max(maxY, q[1]);
  }
  canvas = cv::Size(static_cast<int>(std::ceil(maxX - minX)) + 1,
                    static_cast<int>(std::ceil(maxY - minY)) + 1);
  return cv::Matx23d(A(0, 0), A(0, 1), -minX, A(1, 0), A(1, 1), -minY);
}

}  // namespace

KeypointHomographyRegistrar::KeypointHomographyRegistrar(const cv::Mat& reference,
                                                         const HomographyTrackerParams& params,
                                                         const RansacParams& ransac)
    : params_(checked(params, ransac)), ransac_(ransac), detector_(makeDetector(params_)) {
  if (reference.empty()) throw Error("keypoint registrar: the reference image is empty");
  norm_ = params_.keypoints == KeypointLayer::Sift ? cv::NORM_L2 : cv::NORM_HAMMING;
  const cv::Mat gray = toGray8(reference);
  if (params_.keypoints == KeypointLayer::Orb) referenceGray_ = gray.clone();
  views_.emplace_back();
  // The reference and its synthetic views at the reference's working scale (a tilted view's
  // smaller canvas is not upsampled: its compression is the point).
  const double referenceScale = workingScale(gray.size());
  detect(gray, referenceScale, views_[0].keypoints, views_[0].descriptors);
  if (static_cast<int>(views_[0].keypoints.size()) < ransac_.minInliers)
    throw Error("keypoint registrar: only " + std::to_string(views_[0].keypoints.size()) + " " +
                keypointLayerName(params_.keypoints) +
                " keypoints in the reference image (at least " +
                std::to_string(ransac_.minInliers) + " needed)");
  // Synthetic tilted views (ASIFT-like): each blurred and warped, searched for keypoints, the
  // positions mapped back into the reference. A ring at kTiltDeg, then a steeper one.
  const auto addTiltView = [&](double tiltDeg, double angle) {
    cv::Size canvas;
    const cv::Matx23d A = tiltMap(gray.size(), tiltDeg, angle, canvas);
    cv::Mat tilted;
    // Anti-aliased compression (ASIFT: a Gaussian of SD 0.8 sqrt(t^2 - 1), t = 1 / cos(tilt),
    // across the compressed direction; isotropic here, which also softens the other direction
    // slightly and keeps it to one OpenCV call).
    cv::Mat blurred;
    const double t = 1.0 / std::cos(tiltDeg * kPi / 180.0);
    const double sigma = 0.8 * std::sqrt(t * t - 1.0);
    cv::GaussianBlur(gray, blurred, cv::Size(), sigma);
    cv::warpAffine(blurred, tilted, A, canvas, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
                   cv::Scalar(0));
    View view;
    detect(tilted, referenceScale, view.keypoints, view.descriptors);
    cv::Matx23d back;
    cv::invertAffineTransform(A, back);
    std::vector<cv::KeyPoint> kept;
    cv::Mat keptDescriptors;
    for (size_t i = 0; i < view.keypoints.size(); ++i) {
      cv::KeyPoint k = view.keypoints[i];
      const cv::Vec3d p(k.pt.x, k.pt.y, 1.0);
      const cv::Vec2d q = back * p;
      if (q[0] < 0 || q[1] < 0 || q[0] > gray.cols - 1 || q[1] > gray.rows - 1) continue;
      k.pt = cv::Point2f(static_cast<float>(q[0]), static_cast<float>(q[1]));
      kept.push_back(k);
      keptDescriptors.push_back(view.descriptors.row(static_cast<int>(i)));
    }
    view.keypoints = std::move(kept);
    view.descriptors = keptDescriptors;
    if (static_cast<int>(view.keypoints.size()) >= ransac_.minInliers)
      views_.push_back(std::move(view));
  };
  for (int v = 0; v < params_.keypointTiltViews; ++v)
    addTiltView(kTiltDeg, kPi * v / params_.keypointTiltViews);
  // The steep ring is turned by half a step against the first: its directions fall between.
  for (int v = 0; v < params_.keypointSteepTiltViews; ++v)
    addTiltView(params_.keypointSteepTiltDeg, kPi * (v + 0.5) / params_.keypointSteepTiltViews);
  if (params_.keypoints == KeypointLayer::Orb && kZoomFinerLevels > 0) {
    // ORB gives level l a share of the features proportional to its area (1.2^-2l): the finer
    // levels take most unless the count grows by about their area, 1.44^levels.
    const int features =
        static_cast<int>(std::lround(params_.keypointFeatures * std::pow(1.44, kZoomFinerLevels)));
    View zoom;
    // At the working scale, like every detection (a large reference reduced first).
    detectAtScale(*cv::ORB::create(features, 1.2f, 8 + kZoomFinerLevels, 31, kZoomFinerLevels),
                  gray, referenceScale, zoom.keypoints, zoom.descriptors);
    if (static_cast<int>(zoom.keypoints.size()) >= ransac_.minInliers)
      views_.push_back(std::move(zoom));
  }
}

void KeypointHomographyRegistrar::detect(const cv::Mat& gray, double scale,
                                         std::vector<cv::KeyPoint>& keypoints,
                                         cv::Mat& descriptors) const {
  const cv::Mat image = resampled(gray, scale);
  detector_->detect(image, keypoints);
  cv::KeyPointsFilter::retainBest(keypoints, params_.keypointFeatures);
  detector_->compute(image, keypoints, descriptors);
  toOriginalPixels(keypoints, scale);
}

KeypointRegistration KeypointHomographyRegistrar::registerFrame(const cv::Mat& frame) const {
  if (frame.empty()) throw Error("keypoint registrar: the frame is empty");
  const cv::Mat gray = toGray8(frame);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  detect(gray, params_.keypointDetectScale * workingScale(gray.size()), keypoints, descriptors);
  // The plain reference first; the tilted views only when it gives no confident homography,
  // then the found homography with the most inliers (or the plain view's failure). Each view's
  // distances are computed once and serve both passes.
  const auto confident = [&](const KeypointRegistration& r) {
    return r.found && r.inliers >= params_.keypointConfidentInliers;
  };
  std::vector<cv::Mat> distances(views_.size());
  KeypointRegistration best;
  for (size_t v = 0; v < views_.size() && !confident(best); ++v) {
    KeypointRegistration r = registerToView(views_[v], gray, keypoints, descriptors,
                                            MatchPass::Distinctive, &distances[v]);
    if (v == 0 || (r.found && (!best.found || r.inliers > best.inliers))) best = std::move(r);
  }
  // A repeated pattern (bricks, tiles, windows) fails the ratio test at its true matches: the
  // next unit looks alike. Without a confident homography, every view is matched once more
  // one-to-one (mutual nearest neighbours, no ratio test) and fitted with MAGSAC++, whose
  // scoring tolerates the many near-duplicate matches.
  for (size_t v = 0; v < views_.size() && !confident(best) && params_.keypointOneToOne; ++v) {
    KeypointRegistration r =
        registerToView(views_[v], gray, keypoints, descriptors, MatchPass::OneToOne, &distances[v]);
    if (r.found && (!best.found || r.inliers > best.inliers)) best = std::move(r);
  }
  // (Not for a frame without texture to match: a black frame costs no dense view.)
  if (!best.found && !referenceGray_.empty() &&
      static_cast<int>(keypoints.size()) >= ransac_.minInliers) {
    KeypointRegistration r = registerDense(gray);
    if (r.found) best = std::move(r);
  }
  return best;
}

KeypointRegistration KeypointHomographyRegistrar::registerDense(const cv::Mat& gray) const {
  std::call_once(*denseOnce_, [&] {
    // ORB's defaults, as for the reference itself, with more keypoints.
    detectAtScale(*cv::ORB::create(params_.keypointFeatures * kDenseFeaturesFactor), referenceGray_,
                  workingScale(referenceGray_.size()), dense_.keypoints, dense_.descriptors);
  });
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  detect(gray, kDenseFrameScale * params_.keypointDetectScale * workingScale(gray.size()),
         keypoints, descriptors);
  return registerToView(dense_, gray, keypoints, descriptors, MatchPass::Distinctive, nullptr);
}

KeypointRegistration KeypointHomographyRegistrar::registerToView(
    const View& view, const cv::Mat& gray, const std::vector<cv::KeyPoint>& keypoints,
    const cv::Mat& descriptors, MatchPass pass, cv::Mat* kept) const {
  KeypointRegistration out;
  out.frameKeypoints = static_cast<int>(keypoints.size());
  if (static_cast<int>(keypoints.size()) < ransac_.minInliers || view.descriptors.empty()) {
    out.failure = "only " + std::to_string(keypoints.size()) + " keypoints in the frame";
    return out;
  }
  // The descriptor distances (frame rows x reference columns): the nearest reference
  // keypoints of each frame keypoint (ratio test) and the nearest frame keypoint of each
  // reference keypoint (mutual check).
  // descriptorDistances, not cv::batchDistance: the same distances, and ORB's Hamming ones with
  // the CPU's popcount (this OpenCV's has none): the finer-level zoom view holds ~4x the keypoints.
  if (kept && kept->empty()) *kept = descriptorDistances(descriptors, view.descriptors, norm_);
  const int rows = descriptors.rows, cols = view.descriptors.rows;
  // Without `kept`: the distances of frame rows [blockStart, blockStart + block.rows).
  cv::Mat block;
  int blockStart = 0;
  std::vector<float> columnBest(static_cast<size_t>(cols), std::numeric_limits<float>::max());
  std::vector<int> columnArg(static_cast<size_t>(cols), -1);
  std::vector<int> rowArg(static_cast<size_t>(rows), -1);
  const float ratio =
      pass == MatchPass::OneToOne ? 1.0f : static_cast<float>(params_.keypointRatio);
  // The ratio test compares the nearest with the nearest elsewhere in the reference: a keypoint
  // the detector found twice at one place (two pyramid levels, or a tilted view) is no rival.
  std::array<std::pair<float, int>, kNearest> nearest;
  for (int r = 0; r < rows; ++r) {
    if (!kept && (block.empty() || r >= blockStart + block.rows)) {
      blockStart = r;
      block = descriptorDistances(descriptors.rowRange(r, std::min(rows, r + kDistanceBlockRows)),
                                  view.descriptors, norm_);
    }
    const float* d = kept ? kept->ptr<float>(r) : block.ptr<float>(r - blockStart);
    nearest.fill({std::numeric_limits<float>::max(), -1});
    for (int c = 0; c < cols; ++c) {
      if (d[c] < nearest.back().first) {
        int k = kNearest - 1;
        while (k > 0 && d[c] < nearest[static_cast<size_t>(k - 1)].first) {
          nearest[static_cast<size_t>(k)] = nearest[static_cast<size_t>(k - 1)];
          --k;
        }
        nearest[static_cast<size_t>(k)] = {d[c], c};
      }
      if (d[c] < columnBest[static_cast<size_t>(c)]) {
        columnBest[static_cast<size_t>(c)] = d[c];
        columnArg[static_cast<size_t>(c)] = r;
      }
    }
    const int arg = nearest[0].second;
    if (arg < 0) continue;
    if (pass == MatchPass::OneToOne) {
      rowArg[static_cast<size_t>(r)] = arg;
      continue;
    }
    const cv::KeyPoint& first = view.keypoints[static_cast<size_t>(arg)];
    const float apart = std::max(kDuplicateMinPx, kDuplicateSizeFraction * first.size);
    float second = nearest.back().first;  // all kNearest at one place: the last stands in
    for (size_t k = 1; k < nearest.size() && nearest[k].second >= 0; ++k) {
      const cv::Point2f delta =
          view.keypoints[static_cast<size_t>(nearest[k].second)].pt - first.pt;
      if (delta.dot(delta) > apart * apart) {
        second = nearest[k].first;
        break;
      }
    }
    if (nearest[0].first < ratio * second) rowArg[static_cast<size_t>(r)] = arg;
  }
  std::vector<cv::Point2f> src, dst;
  for (int r = 0; r < rows; ++r) {
    const int c = rowArg[static_cast<size_t>(r)];
    if (c < 0 || columnArg[static_cast<size_t>(c)] != r) continue;
    src.push_back(view.keypoints[static_cast<size_t>(c)].pt);
    dst.push_back(keypoints[static_cast<size_t>(r)].pt);
  }
  out.matches = static_cast<int>(src.size());
  if (out.matches < ransac_.minInliers) {
    out.failure = "only " + std::to_string(out.matches) + " keypoint matches";
    return out;
  }
  std::vector<uchar> mask;
  const double threshold = params_.keypointInlierThresholdPx * resolutionScale(gray.size());
  const cv::Mat H = cv::findHomography(
      src, dst, pass == MatchPass::OneToOne ? cv::USAC_MAGSAC : cv::RANSAC, threshold, mask,
      ransacIterations(out.matches, std::max(4, ransac_.minInliers)), kRansacConfidence);
  if (H.empty()) {
    out.failure = "no keypoint homography";
    return out;
  }
  for (uchar m : mask) out.inliers += m ? 1 : 0;
  out.H = cv::Matx33d(H) * (1.0 / H.at<double>(2, 2));
  if (out.inliers < ransac_.minInliers) {
    out.failure = "only " + std::to_string(out.inliers) + " keypoint inliers";
    return out;
  }
  // The view must be a plane in front of the camera (w > 0 at every inlier) and not degenerate
  // where the inliers are: the area ratio (Jacobian determinant) at their centroid within
  // [1 / kMaxAreaRatio, kMaxAreaRatio]. (det H itself is the area ratio at the reference's
  // origin, which a zoomed, tilted view legitimately pushes past any bound.)
  cv::Point2d centroid(0, 0);
  bool inFront = true;
  for (size_t i = 0; i < src.size(); ++i) {
    if (!mask[i]) continue;
    centroid += cv::Point2d(src[i].x, src[i].y) * (1.0 / out.inliers);
    inFront = inFront && out.H(2, 0) * src[i].x + out.H(2, 1) * src[i].y + out.H(2, 2) > 0;
  }
  const double w =
      out.H(2, 0) * centroid.x + out.H(2, 1) * centroid.y + out.H(2, 2);  // area ratio: det/w^3
  const double areaRatio = cv::determinant(out.H) / (w * w * w);
  if (!inFront || !std::isfinite(areaRatio) || areaRatio < 1.0 / kMaxAreaRatio ||
      areaRatio > kMaxAreaRatio) {
    out.failure = "degenerate keypoint homography";
    return out;
  }
  for (size_t i = 0; i < dst.size(); ++i)
    if (mask[i]) out.inlierPoints.push_back(dst[i]);
  out.found = true;
  return out;
}

}  // namespace reftrack
