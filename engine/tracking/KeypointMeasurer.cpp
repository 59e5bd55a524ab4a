#include "engine/tracking/KeypointMeasurer.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>
#include <optional>
#include <random>
#include <utility>

#include "engine/core/Error.hpp"
#include "engine/geometry/AffineFit.hpp"

namespace reftrack {

namespace {

// The points whose projections give a point's local warp: it and these nearest of its reference.
constexpr int kNeighbours = 6;

}  // namespace

KeypointMeasurer::KeypointMeasurer(PinholeCamera camera, std::vector<MeasurableKeypoint> points,
                                   const cv::Mat& grayA, const cv::Mat& grayB,
                                   PatchAlignerParams params)
    : camera_(std::move(camera)), points_(std::move(points)), alignerParams_(params) {
  alignerParams_.check();
  if (grayA.type() != CV_8UC1 || grayB.type() != CV_8UC1)
    throw Error("KeypointMeasurer: references must be 8-bit grey");
  grays_[0] = grayA;
  grays_[1] = grayB;
  index();
}

void KeypointMeasurer::index() {
  neighbours_.assign(points_.size(), {});
  std::vector<std::pair<float, int>> byDistance;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    byDistance.clear();
    for (std::size_t j = 0; j < points_.size(); ++j) {
      if (j == i || points_[j].reference != points_[i].reference) continue;
      const cv::Point2f d = points_[j].pixel - points_[i].pixel;
      byDistance.emplace_back(d.dot(d), static_cast<int>(j));
    }
    const std::size_t take = std::min<std::size_t>(kNeighbours, byDistance.size());
    std::partial_sort(byDistance.begin(), byDistance.begin() + static_cast<long>(take),
                      byDistance.end());
    for (std::size_t j = 0; j < take; ++j) neighbours_[i].push_back(byDistance[j].second);
  }
  order_.resize(points_.size());
  std::iota(order_.begin(), order_.end(), 0);
  std::shuffle(order_.begin(), order_.end(), std::mt19937(33));
}

int KeypointMeasurer::dropPointsFailingBetweenReferences(const RigidPose& T_AB) {
  std::vector<char> failed(points_.size(), 0);
  for (int r = 0; r < 2; ++r) {
    // Reference r's points measured in the other's image, that camera the frame.
    std::vector<char> tried;
    std::vector<char> aligned(points_.size(), 0);
    const RigidPose toOther = r == 0 ? T_AB : RigidPose::identity();
    for (const KeypointMeasurement& m : measure(grays_[1 - r], toOther, 0, r, &tried))
      aligned[static_cast<std::size_t>(m.point)] = 1;
    for (std::size_t i = 0; i < points_.size(); ++i)
      if (tried[i] && !aligned[i]) failed[i] = 1;
  }
  std::vector<MeasurableKeypoint> kept;
  for (std::size_t i = 0; i < points_.size(); ++i)
    if (!failed[i]) kept.push_back(points_[i]);
  const int dropped = static_cast<int>(points_.size() - kept.size());
  points_ = std::move(kept);
  index();
  return dropped;
}

std::vector<KeypointMeasurement> KeypointMeasurer::measure(const cv::Mat& gray8,
                                                           const RigidPose& T_Ak, int cap) const {
  return measure(gray8, T_Ak, cap, -1, nullptr);
}

std::vector<KeypointMeasurement> KeypointMeasurer::measure(const cv::Mat& gray8,
                                                           const RigidPose& T_Ak, int cap,
                                                           int reference,
                                                           std::vector<char>* tried) const {
  std::vector<KeypointMeasurement> out;
  if (tried) tried->assign(points_.size(), 0);
  if (points_.empty()) return out;
  if (gray8.type() != CV_8UC1) throw Error("KeypointMeasurer: the frame must be 8-bit grey");
  // Every point's projection through the lens in one call (NaN behind the camera).
  std::vector<cv::Point3d> inCamera(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Eigen::Vector3d X = T_Ak * points_[i].pointA;
    inCamera[i] = {X.x(), X.y(), X.z()};
  }
  std::vector<cv::Point2d> projected;
  cv::projectPoints(inCamera, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera_.Kcv(),
                    camera_.distortion(), projected);
  for (std::size_t i = 0; i < projected.size(); ++i)
    if (!(inCamera[i].z > 1e-6)) projected[i] = {NAN, NAN};
  const double margin = alignerParams_.halfWindow + alignerParams_.maxShiftPx + 2.0;
  // First the alignments to try (in the visiting order, up to the cap), then the alignments
  // themselves, split over OpenCV's threads: each aligns its own share with its own aligner
  // (scratch) and writes its own slots, so the result is the same on any number of threads.
  struct Alignment {
    std::size_t point;
    cv::Matx22d J;  // frame offsets -> reference offsets
    cv::Point2d start;
  };
  std::vector<Alignment> planned;
  std::vector<std::pair<cv::Point2d, cv::Point2d>> pairs;
  for (const int visit : order_) {
    if (cap > 0 && static_cast<int>(planned.size()) >= cap) break;
    const auto i = static_cast<std::size_t>(visit);
    if (reference >= 0 && points_[i].reference != reference) continue;
    const cv::Point2d pK = projected[i];
    if (!(pK.x >= margin && pK.y >= margin && pK.x < gray8.cols - margin &&
          pK.y < gray8.rows - margin))
      continue;
    cv::Matx33d referenceToK;
    const auto pixelOf = [&](std::size_t k) { return points_[k].pixel; };
    if (fitLocalAffine(i, neighbours_[i], pixelOf, projected, pairs, referenceToK) !=
        AffineFit::Fitted)
      continue;
    const cv::Matx22d toK(referenceToK(0, 0), referenceToK(0, 1), referenceToK(1, 0),
                          referenceToK(1, 1));
    planned.push_back({i, toK.inv(), pK});
    if (tried) (*tried)[i] = 1;
  }
  std::vector<std::optional<PatchAlignment>> aligned(planned.size());
  // One share per thread; an alignment is ~2 us, so a share below ~32 is not worth a task.
  const int shares =
      std::clamp(static_cast<int>(planned.size()) / 32, 1, std::max(1, cv::getNumThreads()));
  cv::parallel_for_(
      cv::Range(0, static_cast<int>(planned.size())),
      [&](const cv::Range& range) {
        const PatchAligner aligner(alignerParams_);
        for (int k = range.start; k < range.end; ++k) {
          const Alignment& a = planned[static_cast<std::size_t>(k)];
          const MeasurableKeypoint& p = points_[a.point];
          aligned[static_cast<std::size_t>(k)] =
              aligner.align(grays_[p.reference], cv::Point2d(p.pixel), a.J, gray8, a.start);
        }
      },
      shares);
  for (std::size_t k = 0; k < planned.size(); ++k) {
    if (!aligned[k]) continue;
    const cv::Point2d& pK = planned[k].start;
    out.push_back({static_cast<int>(planned[k].point), aligned[k]->position,
                   cv::Point2f(static_cast<float>(pK.x), static_cast<float>(pK.y)),
                   aligned[k]->sigmaPx});
  }
  return out;
}

}  // namespace reftrack
