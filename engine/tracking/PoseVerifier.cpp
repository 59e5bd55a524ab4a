#include "engine/tracking/PoseVerifier.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <opencv2/calib3d.hpp>
#include <random>
#include <utility>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/AffineFit.hpp"
#include "engine/tracking/WarpedCorrelation.hpp"

namespace reftrack {

namespace {

// Map points whose neighbours' projections give a point's local warp: the point and these.
constexpr int kNeighbours = 6;

// The k nearest other points of each point (by image distance), nearest first.
std::vector<std::vector<int>> nearestNeighbours(const std::vector<cv::Point2f>& pixels, int k) {
  std::vector<std::vector<int>> out(pixels.size());
  std::vector<std::pair<float, int>> byDistance;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    byDistance.clear();
    if (!std::isfinite(pixels[i].x)) continue;
    for (std::size_t j = 0; j < pixels.size(); ++j) {
      if (j == i || !std::isfinite(pixels[j].x)) continue;
      const cv::Point2f d = pixels[j] - pixels[i];
      byDistance.emplace_back(d.dot(d), static_cast<int>(j));
    }
    const std::size_t take = std::min<std::size_t>(static_cast<std::size_t>(k), byDistance.size());
    std::partial_sort(byDistance.begin(), byDistance.begin() + static_cast<long>(take),
                      byDistance.end());
    for (std::size_t j = 0; j < take; ++j) out[i].push_back(byDistance[j].second);
  }
  return out;
}

// The best NCC of `warped` (zero-mean, unit-norm, side x side) with the frame's side x side
// windows centred at `centre` + each offset (whole pixels), nearest first, stopping at the first
// at or above `enough`. The frame is read once as a patch with its summed-area tables, so each
// offset costs one dot product (this check runs on every tracked frame).
float bestWindowScore(const cv::Mat& gray8, cv::Point centre, int n, int reach,
                      const std::vector<cv::Point>& offsets, const float* warped, float enough) {
  const int side = 2 * n + 1, size = side + 2 * reach, count = side * side;
  thread_local std::vector<float> patch;
  thread_local std::vector<double> sum, squares;
  patch.resize(static_cast<std::size_t>(size * size));
  sum.assign(static_cast<std::size_t>((size + 1) * (size + 1)), 0.0);
  squares.assign(sum.size(), 0.0);
  const int x0 = centre.x - n - reach, y0 = centre.y - n - reach;
  for (int r = 0; r < size; ++r) {
    const uchar* row = gray8.ptr<uchar>(y0 + r) + x0;
    double rowSum = 0.0, rowSquares = 0.0;
    for (int c = 0; c < size; ++c) {
      const float v = row[c];
      patch[static_cast<std::size_t>(r * size + c)] = v;
      rowSum += v;
      rowSquares += static_cast<double>(v) * v;
      const auto at = static_cast<std::size_t>((r + 1) * (size + 1) + c + 1);
      sum[at] = sum[at - static_cast<std::size_t>(size + 1)] + rowSum;
      squares[at] = squares[at - static_cast<std::size_t>(size + 1)] + rowSquares;
    }
  }
  const auto box = [&](const std::vector<double>& t, int x, int y) {
    const auto w = static_cast<std::size_t>(size + 1);
    const auto X = static_cast<std::size_t>(x), Y = static_cast<std::size_t>(y);
    const auto S = static_cast<std::size_t>(side);
    return t[(Y + S) * w + X + S] - t[Y * w + X + S] - t[(Y + S) * w + X] + t[Y * w + X];
  };
  float best = -1.0f;
  for (const cv::Point& o : offsets) {
    const int x = reach + o.x, y = reach + o.y;
    const double s = box(sum, x, y);
    const double variance = box(squares, x, y) - s * s / count;
    if (!(variance >= 0.25 * count)) continue;  // flat (as sampleFrameWindow)
    float dot = 0.0f;
    for (int r = 0; r < side; ++r) {
      const float* f = patch.data() + (y + r) * size + x;
      const float* w = warped + r * side;
      for (int c = 0; c < side; ++c) dot += w[c] * f[c];
    }
    best = std::max(best, static_cast<float>(dot / std::sqrt(variance)));
    if (best >= enough) break;
  }
  return best;
}

}  // namespace

PoseVerifier::PoseVerifier(PinholeCamera camera, std::vector<Eigen::Vector3d> pointsA,
                           const RigidPose& T_AB, VerifiedReference a, VerifiedReference b,
                           PoseVerifierParams params)
    : camera_(std::move(camera)),
      pointsA_(std::move(pointsA)),
      T_AB_(T_AB),
      refs_{std::move(a), std::move(b)},
      params_(params) {
  for (int r = 0; r < 2; ++r) {
    const VerifiedReference& ref = refs_[r];
    if (ref.pixels.size() != pointsA_.size() || ref.distinctive.size() != pointsA_.size())
      throw Error("PoseVerifier: one pixel and one distinctive flag per map point are needed");
    if (ref.gray8.type() != CV_8UC1) throw Error("PoseVerifier: references must be 8-bit grey");
    neighbours_[r] = nearestNeighbours(ref.pixels, kNeighbours);
  }
  // A fixed shuffled order: the first maxChecked checkable points are a sample spread at random
  // over the scene.
  order_.resize(pointsA_.size());
  std::iota(order_.begin(), order_.end(), 0);
  std::shuffle(order_.begin(), order_.end(), std::mt19937(12345));
}

PoseCheck PoseVerifier::check(const cv::Mat& gray8, const RigidPose& T_Ak) const {
  const auto start = std::chrono::steady_clock::now();
  PoseCheck out;
  if (gray8.type() != CV_8UC1) throw Error("PoseVerifier: the frame must be 8-bit grey");
  const int n = params_.halfWindow;
  // The reference nearer the frame's viewpoint: its windows need the milder warp.
  const Eigen::Vector3d centreK = T_Ak.cameraCentre();
  const Eigen::Vector3d centreB = T_AB_.cameraCentre();
  out.reference = (centreK - centreB).norm() < centreK.norm() ? 1 : 0;
  const VerifiedReference& ref = refs_[out.reference];
  const std::vector<std::vector<int>>& neighbours = neighbours_[out.reference];

  // Every point's projection (NaN behind the camera), through the lens in one call (a call per
  // point cost a millisecond for the ~900 points of a map with its keypoints).
  std::vector<cv::Point3d> inCamera(pointsA_.size());
  for (std::size_t i = 0; i < pointsA_.size(); ++i) {
    const Eigen::Vector3d X = T_Ak * pointsA_[i];
    inCamera[i] = {X.x(), X.y(), X.z()};
  }
  std::vector<cv::Point2d> projected;
  if (!inCamera.empty())
    cv::projectPoints(inCamera, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera_.Kcv(),
                      camera_.distortion(), projected);
  for (std::size_t i = 0; i < projected.size(); ++i)
    if (!(inCamera[i].z > 1e-6)) projected[i] = {NAN, NAN};
  // The search: whole-pixel offsets within searchPx (scaled) around the projection, the best
  // score kept (the pose and the map point are each good to a pixel or so, not to the sample).
  const int maxChecked = params_.maxChecked;
  const int reach = static_cast<int>(std::ceil(params_.searchPx * resolutionScale(gray8.size())));
  const double margin = n + reach + 2.0;
  // Offsets nearest first: a confirmed point usually stops at the first few.
  std::vector<cv::Point> offsets;
  for (int dy = -reach; dy <= reach; ++dy)
    for (int dx = -reach; dx <= reach; ++dx)
      if (dx * dx + dy * dy <= reach * reach) offsets.emplace_back(dx, dy);
  std::stable_sort(offsets.begin(), offsets.end(), [](cv::Point a, cv::Point b) {
    return a.x * a.x + a.y * a.y < b.x * b.x + b.y * b.y;
  });
  const int side = 2 * n + 1, count = side * side;
  std::vector<float> warped(static_cast<std::size_t>(count));
  std::vector<std::pair<cv::Point2d, cv::Point2d>> pairs;
  for (const int visit : order_) {
    if (out.checkable >= maxChecked) break;
    const auto i = static_cast<std::size_t>(visit);
    if (!ref.distinctive[i]) continue;
    const cv::Point2d pK = projected[i];
    if (!(pK.x >= margin && pK.y >= margin && pK.x < gray8.cols - margin &&
          pK.y < gray8.rows - margin))
      continue;
    cv::Matx33d referenceToK;
    const auto pixelOf = [&](std::size_t k) { return ref.pixels[k]; };
    if (fitLocalAffine(i, neighbours[i], pixelOf, projected, pairs, referenceToK) !=
        AffineFit::Fitted)
      continue;
    const cv::Matx33d W = referenceToK.inv();  // frame -> reference
    // The frame is read at whole pixels: the reference window is sampled where W puts the whole
    // pixel nearest the projection.
    const cv::Point centre(static_cast<int>(std::lround(pK.x)),
                           static_cast<int>(std::lround(pK.y)));
    const cv::Vec3d a = W * cv::Vec3d(pK.x, pK.y, 1.0), b = W * cv::Vec3d(centre.x, centre.y, 1.0);
    const cv::Point2d pR = cv::Point2d(ref.pixels[i]) +
                           cv::Point2d(b[0] / b[2] - a[0] / a[2], b[1] / b[2] - a[1] / a[2]);
    if (!sampleWarpedReferenceWindow(ref.gray8, W, cv::Point2d(centre), pR, n, warped.data()))
      continue;
    ++out.checkable;
    const float minScore = static_cast<float>(params_.minScore);
    const float best = bestWindowScore(gray8, centre, n, reach, offsets, warped.data(), minScore);
    if (best >= minScore) ++out.confirmed;
    // Confirmed whatever the rest of the sample shows: enough.
    if (out.confirmed >= params_.minConfirmed &&
        out.confirmed >= params_.minConfirmedShare * maxChecked)
      break;
  }
  out.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const int needed = std::max(
      params_.minConfirmed,
      static_cast<int>(std::ceil(params_.minConfirmedShare * static_cast<double>(out.checkable))));
  if (out.confirmed >= needed) return out;
  const bool unsure = out.confirmed >= params_.minUnsure &&
                      static_cast<double>(out.confirmed) >= params_.minUnsureShare * out.checkable;
  out.verdict = unsure ? PoseCheck::Verdict::Unsure : PoseCheck::Verdict::Refuted;
  out.reason = "the pose is not confirmed by the reference: " + std::to_string(out.confirmed) +
               " of the " + std::to_string(out.checkable) +
               " distinctive map points it projects into the frame correlate there, " +
               std::to_string(needed) + " needed (pose.verify_min_points, verify_min_share)";
  return out;
}

}  // namespace reftrack
