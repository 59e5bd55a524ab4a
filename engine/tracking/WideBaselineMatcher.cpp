#include "engine/tracking/WideBaselineMatcher.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/geometry/AffineFit.hpp"
#include "engine/tracking/WarpedCorrelation.hpp"

namespace reftrack {

MatchableReference MatchableReference::build(const cv::Mat& image, std::vector<cv::Point2f> corners,
                                             const std::vector<char>& preferred) {
  if (image.empty()) throw Error("MatchableReference: empty reference image");
  if (!preferred.empty() && preferred.size() != corners.size())
    throw Error("MatchableReference: one preference flag per corner is required");
  MatchableReference r;
  r.gray8 = toGray8(image);
  r.corners = std::move(corners);
  r.grid = CornerGrid(r.corners, image.size(), 32);
  // Round robin over the cells of an 8x6 grid, preferred corners first.
  constexpr int kColumns = 8, kRows = 6;
  for (const bool wantPreferred : {true, false}) {
    std::vector<std::vector<int>> cells(kColumns * kRows);
    for (int i = 0; i < static_cast<int>(r.corners.size()); ++i) {
      const bool isPreferred = preferred.empty() || preferred[static_cast<std::size_t>(i)];
      if (isPreferred != wantPreferred) continue;
      const cv::Point2f& p = r.corners[static_cast<std::size_t>(i)];
      const int cx = std::clamp(static_cast<int>(p.x * kColumns / image.cols), 0, kColumns - 1);
      const int cy = std::clamp(static_cast<int>(p.y * kRows / image.rows), 0, kRows - 1);
      cells[static_cast<std::size_t>(cy * kColumns + cx)].push_back(i);
    }
    for (std::size_t round = 0;; ++round) {
      bool any = false;
      for (const std::vector<int>& cell : cells)
        if (round < cell.size()) {
          r.order.push_back(cell[round]);
          any = true;
        }
      if (!any) break;
    }
  }
  return r;
}

MatchableFrame MatchableFrame::build(const cv::Mat& image, std::vector<cv::Point2f> corners,
                                     int halfWindow) {
  if (image.empty()) throw Error("MatchableFrame: empty frame");
  if (halfWindow < 1) throw Error("MatchableFrame: halfWindow must be >= 1");
  cv::Mat gray = image;
  if (image.channels() == 3) cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  if (gray.type() != CV_8UC1) throw Error("MatchableFrame: the frame must be 8-bit grey or BGR");
  MatchableFrame f;
  f.size = gray.size();
  f.halfWindow = halfWindow;
  f.corners = std::move(corners);
  f.grid = CornerGrid(f.corners, f.size, 32);
  const int side = 2 * halfWindow + 1;
  f.windows.resize(f.corners.size() * static_cast<std::size_t>(side * side));
  f.valid.resize(f.corners.size());
  for (std::size_t i = 0; i < f.corners.size(); ++i)
    f.valid[i] = sampleFrameWindow(gray, cv::Point2d(f.corners[i]), halfWindow,
                                   f.windows.data() + i * static_cast<std::size_t>(side * side));
  return f;
}

namespace {

inline cv::Point2d apply(const cv::Matx33d& M, cv::Point2d p) {
  const cv::Vec3d q = M * cv::Vec3d(p.x, p.y, 1.0);
  return {q[0] / q[2], q[1] / q[2]};
}

// The derivative of p -> M p (homogeneous) at p.
cv::Matx22d jacobianAt(const cv::Matx33d& M, cv::Point2d p) {
  const cv::Vec3d q = M * cv::Vec3d(p.x, p.y, 1.0);
  const double x = q[0] / q[2], y = q[1] / q[2];
  return cv::Matx22d(M(0, 0) - x * M(2, 0), M(0, 1) - x * M(2, 1), M(1, 0) - y * M(2, 0),
                     M(1, 1) - y * M(2, 1)) *
         (1.0 / q[2]);
}

// Least-squares affine map src -> dst at `p` from the pairs listed in `nearby` nearest to p (in
// src): k of them, more (up to 8) when the nearest are nearly collinear. False when degenerate.
bool fitLocalAffine(cv::Point2d p, const std::vector<cv::Point2f>& src,
                    const std::vector<cv::Point2f>& dst, const std::vector<int>& nearby, int k,
                    cv::Matx33d& L) {
  if (static_cast<int>(nearby.size()) < 3) return false;
  thread_local std::vector<std::pair<double, int>> byDistance;
  byDistance.clear();
  for (int i : nearby) {
    const cv::Point2d d = cv::Point2d(src[static_cast<std::size_t>(i)]) - p;
    byDistance.emplace_back(d.dot(d), i);
  }
  const int available = static_cast<int>(byDistance.size());
  const int most = std::min(std::max(k, 8), available);
  // Sorted lazily: the first k nearest suffice unless they are collinear, and the pairs (with
  // their distinct indices) have one sorted order, so the neighbours are those of a full
  // partial_sort to `most` (which cost a third of this function on the real postcard clip).
  int sorted = std::min(k, available);
  std::partial_sort(byDistance.begin(), byDistance.begin() + sorted, byDistance.end());
  for (int count = std::min(k, available); count <= most; ++count) {
    for (; sorted < count; ++sorted)
      std::iter_swap(byDistance.begin() + sorted,
                     std::min_element(byDistance.begin() + sorted, byDistance.end()));
    const auto pairAt = [&](int j) {
      const auto i = static_cast<std::size_t>(byDistance[static_cast<std::size_t>(j)].second);
      return std::pair<cv::Point2f, cv::Point2f>(src[i], dst[i]);
    };
    const AffineFit fit = fitAffine(count, pairAt, L);
    if (fit == AffineFit::Collinear || fit == AffineFit::TooFew) continue;  // try more pairs
    return fit == AffineFit::Fitted;
  }
  return false;
}

// The local affine map reference -> previous frame (L^-1 of Eq. 18) at a reference corner, from
// the previous matches nearest it: those in the smallest square of half-side 40 px * 2^j around
// it that holds at least 8 of them (or all), the affineNeighbours nearest of those fitted
// (fitLocalAffine). The square is found by one scan of the previous matches' Chebyshev distances,
// not by widening queries of a bucket grid (two or three per corner): desk clip, 752x480, ~100
// previous matches, the stages match A + match B 0.573 -> 0.530 ms per frame (medians, `track
// --out-csv`). The same sets, so the same matches (fitLocalAffine orders them by distance and
// index, whatever order they come in).
class NearestPreviousAffine {
 public:
  NearestPreviousAffine(const std::vector<PreviousMatch>& previous,
                        const MatchableReference& reference, int neighbours)
      : widest_(4.0 * reference.gray8.cols), neighbours_(neighbours) {
    for (const PreviousMatch& m : previous) {
      inReference_.push_back(reference.corners.at(static_cast<std::size_t>(m.referenceCorner)));
      inPrevious_.push_back(m.previous);
    }
    squareReach_.resize(previous.size());
  }

  std::optional<cv::Matx33d> at(cv::Point2d pA) {
    for (std::size_t i = 0; i < inReference_.size(); ++i)
      squareReach_[i] =
          std::max(std::abs(inReference_[i].x - pA.x), std::abs(inReference_[i].y - pA.y));
    double half = 40.0;
    for (;; half *= 2.0) {
      const auto within = static_cast<std::size_t>(std::count_if(
          squareReach_.begin(), squareReach_.end(), [half](double r) { return r <= half; }));
      if (within >= 8 || within == squareReach_.size() || half > widest_) break;
    }
    nearby_.clear();
    for (std::size_t i = 0; i < squareReach_.size(); ++i)
      if (squareReach_[i] <= half) nearby_.push_back(static_cast<int>(i));
    cv::Matx33d L;
    if (!fitLocalAffine(pA, inReference_, inPrevious_, nearby_, neighbours_, L))
      return std::nullopt;
    return L;
  }

 private:
  std::vector<cv::Point2f> inReference_, inPrevious_;  // the previous matches' pairs
  std::vector<double> squareReach_;
  std::vector<int> nearby_;
  double widest_;
  int neighbours_;
};

}  // namespace

bool WideBaselineMatcher::localAffine(cv::Point2d p, const std::vector<PreviousMatch>& previous,
                                      const MatchableReference& reference, cv::Matx33d& L) const {
  std::vector<cv::Point2f> src, dst;
  std::vector<int> all;
  for (const PreviousMatch& m : previous) {
    all.push_back(static_cast<int>(src.size()));
    src.push_back(m.previous);
    dst.push_back(reference.corners.at(static_cast<std::size_t>(m.referenceCorner)));
  }
  return fitLocalAffine(p, src, dst, all, params_.affineNeighbours, L);
}

MapsToPrevious WideBaselineMatcher::mapsToPrevious(const std::vector<PreviousMatch>& previous,
                                                   const MatchableReference& reference,
                                                   std::size_t count) const {
  MapsToPrevious maps;
  if (previous.size() < 3 || reference.corners.empty()) return maps;
  NearestPreviousAffine affine(previous, reference, params_.affineNeighbours);
  for (std::size_t i = 0; i < std::min(count, reference.order.size()); ++i)
    maps.atOrder.push_back(
        affine.at(cv::Point2d(reference.corners[static_cast<std::size_t>(reference.order[i])])));
  return maps;
}

std::vector<WideBaselineMatch> WideBaselineMatcher::match(
    const MatchableFrame& frame, const cv::Matx33d& H_kToPrev,
    const std::vector<PreviousMatch>& previous, const MatchableReference& reference,
    const MapsToPrevious* computed) const {
  std::vector<WideBaselineMatch> matches;
  if (previous.size() < 3 || frame.corners.empty() || reference.corners.empty()) return matches;
  if (frame.halfWindow != params_.halfWindow)
    throw Error(
        "WideBaselineMatcher: the frame's windows have n = " + std::to_string(frame.halfWindow) +
        ", the parameters n = " + std::to_string(params_.halfWindow));
  const double detH = cv::determinant(H_kToPrev);
  if (!std::isfinite(detH) || std::abs(detH) < 1e-9) return matches;
  const cv::Matx33d prevToK = H_kToPrev.inv();
  const double scale = resolutionScale(frame.size);
  const double hx = params_.dx * scale, hy = params_.dy * scale;
  const int n = params_.halfWindow, side = 2 * n + 1, count = side * side;
  // L^-1 at each corner: given for a prefix of the order (computed while H was), the rest here
  // (the previous matches' pairs set up only when a corner past the prefix is reached).
  std::optional<NearestPreviousAffine> affine;
  const std::size_t given = computed ? computed->atOrder.size() : 0;

  // First the reference corners to try, in MatchableReference::order up to the cap, each with
  // its predicted frame position; then their windows, sampled and scored in the order of their
  // place in the reference (bands of rows): the round-robin order jumps across the reference at
  // every corner, and at 1280x720 the cache misses of those jumps were most of the sampling's
  // time (perf, 6-DOF handheld webcam sequence). Only exact score ties could pair differently.
  struct Tried {
    int corner;
    cv::Matx33d referenceToK;
    cv::Matx33d W;  // frame -> reference
    cv::Point2d pK;
  };
  thread_local std::vector<Tried> tried;
  tried.clear();
  std::vector<int> candidates;
  const int cap = params_.referenceCornersFor(frame.size);
  for (std::size_t place = 0; place < reference.order.size(); ++place) {
    if (cap > 0 && static_cast<int>(tried.size()) >= cap) break;
    const int c = reference.order[place];
    const cv::Point2d pA(reference.corners[static_cast<std::size_t>(c)]);
    if (place >= given && !affine) affine.emplace(previous, reference, params_.affineNeighbours);
    const std::optional<cv::Matx33d> LInverse =  // reference -> previous frame
        place < given ? computed->atOrder[place] : affine->at(pA);
    if (!LInverse) continue;
    const cv::Matx33d referenceToK = prevToK * *LInverse;  // W^-1
    const cv::Point2d pK = apply(referenceToK, pA);
    if (!(pK.x >= 0 && pK.y >= 0 && pK.x < frame.size.width && pK.y < frame.size.height)) continue;
    tried.push_back({c, referenceToK, referenceToK.inv(), pK});
  }
  constexpr int kBandRows = 16;
  const auto placeOf = [&](const Tried& t) {
    const cv::Point2f& p = reference.corners[static_cast<std::size_t>(t.corner)];
    return std::pair(static_cast<int>(p.y) / kBandRows, p.x);
  };
  std::sort(tried.begin(), tried.end(),
            [&](const Tried& a, const Tried& b) { return placeOf(a) < placeOf(b); });

  std::vector<float> warped(static_cast<std::size_t>(count));
  std::vector<WideBaselineMatch> bestPerFrame(frame.corners.size());
  for (std::size_t i = 0; i < tried.size(); ++i) {
    const Tried& t = tried[i];
    // The next window's reference pixels are fetched while this one is scored.
    if (i + 1 < tried.size())
      prefetchWarpedReferenceWindow(
          reference.gray8, tried[i + 1].W, tried[i + 1].pK,
          cv::Point2d(reference.corners[static_cast<std::size_t>(tried[i + 1].corner)]), n);
    frame.grid.query(t.pK, hx, hy, candidates);
    if (candidates.empty()) continue;
    const cv::Point2d pA(reference.corners[static_cast<std::size_t>(t.corner)]);
    if (!sampleWarpedReferenceWindow(reference.gray8, t.W, t.pK, pA, n, warped.data())) continue;
    float bestScore = static_cast<float>(params_.minScore);
    int bestFrame = -1;
    for (int f : candidates) {
      if (!frame.valid[static_cast<std::size_t>(f)]) continue;
      const float s = windowScore(frame.window(f), warped.data(), count);
      if (s > bestScore) {
        bestScore = s;
        bestFrame = f;
      }
    }
    if (bestFrame < 0) continue;
    WideBaselineMatch& slot = bestPerFrame[static_cast<std::size_t>(bestFrame)];
    if (slot.frameCorner < 0 || bestScore > slot.score)
      slot = {bestFrame, t.corner, bestScore, t.pK, jacobianAt(t.W, t.pK)};
  }
  for (const WideBaselineMatch& m : bestPerFrame)
    if (m.frameCorner >= 0) matches.push_back(m);
  return matches;
}

}  // namespace reftrack
