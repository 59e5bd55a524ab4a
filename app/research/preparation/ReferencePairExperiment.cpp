#include "app/research/preparation/ReferencePairExperiment.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"
#include "engine/core/ThreadCpuClock.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/geometry/FundamentalMatrix.hpp"
#include "engine/matching/NccCorrelation.hpp"
#include "engine/reference/MultiReferencePreparer.hpp"
#include "engine/reference/TwoViewTriangulator.hpp"
#include "engine/tracking/MultiReferenceTracker.hpp"

namespace reftrack::app {

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t k =
      std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5));
  return v[k];
}

double shareBelow(const std::vector<double>& v, double limit) {
  if (v.empty()) return std::nan("");
  return static_cast<double>(
             std::count_if(v.begin(), v.end(), [&](double x) { return x < limit; })) /
         static_cast<double>(v.size());
}

void printDistribution(const char* what, const std::vector<double>& d) {
  std::printf(
      "  %s: %zu, median %.2f px, p75 %.2f, p90 %.2f; < 1 px %.0f%%, < 2 px %.0f%%, < 3 px "
      "%.0f%%\n",
      what, d.size(), quantile(d, 0.5), quantile(d, 0.75), quantile(d, 0.9),
      100.0 * shareBelow(d, 1.0), 100.0 * shareBelow(d, 2.0), 100.0 * shareBelow(d, 3.0));
}

double epipolarDistance(const Eigen::Matrix3d& F, const cv::Point2f& a, const cv::Point2f& b) {
  const Eigen::Vector3d line = F * Eigen::Vector3d(a.x, a.y, 1.0);
  return std::abs(line.dot(Eigen::Vector3d(b.x, b.y, 1.0))) / line.head<2>().norm();
}

// Mutual SIFT matches passing Lowe's ratio test (0.75), as the per-frame peers match.
void siftMatches(const cv::Mat& grayA, const cv::Mat& grayB, std::vector<cv::Point2f>& a,
                 std::vector<cv::Point2f>& b) {
  const cv::Ptr<cv::SIFT> sift = cv::SIFT::create();
  std::vector<cv::KeyPoint> kA, kB;
  cv::Mat dA, dB;
  sift->detectAndCompute(grayA, cv::noArray(), kA, dA);
  sift->detectAndCompute(grayB, cv::noArray(), kB, dB);
  if (kA.size() < 2 || kB.size() < 2) return;
  cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> ab, ba;
  matcher.knnMatch(dA, dB, ab, 2);
  matcher.knnMatch(dB, dA, ba, 2);
  for (const std::vector<cv::DMatch>& m : ab) {
    if (m.size() < 2 || m[0].distance >= 0.75f * m[1].distance) continue;
    const std::vector<cv::DMatch>& back = ba[static_cast<std::size_t>(m[0].trainIdx)];
    if (back.empty() || back[0].trainIdx != m[0].queryIdx) continue;
    a.push_back(kA[static_cast<std::size_t>(m[0].queryIdx)].pt);
    b.push_back(kB[static_cast<std::size_t>(m[0].trainIdx)].pt);
  }
}

// A 3D point (world) with the reference pixel (with distortion) its window is taken from.
struct CheckedPoint {
  Eigen::Vector3d world;
  int view;  // 0: reference A, 1: reference B
  cv::Point2f pixel;
};

// Offsets (pixels) of the warped-NCC peaks from the projections of `points` into a frame with
// true pose T_k; the points not found (score below minScore, or the peak on the search border)
// are counted in `missed`.
std::vector<double> offsetsInFrame(const PinholeCamera& camera, const std::vector<cv::Mat>& refGray,
                                   const std::vector<RigidPose>& refPose,
                                   const std::vector<CheckedPoint>& points, const cv::Mat& gray,
                                   const RigidPose& T_k, int radius, double minScore, int& missed) {
  constexpr int kHalfWindow = 7;
  std::vector<double> offsets;
  const Eigen::Matrix3d K = camera.K(), Kinv = K.inverse();
  for (const CheckedPoint& p : points) {
    const RigidPose& T_r = refPose[static_cast<std::size_t>(p.view)];
    const Eigen::Vector3d Xr = T_r * p.world, Xk = T_k * p.world;
    if (!(Xk.z() > 0.05)) continue;
    const Eigen::Vector2d projected = camera.projectDistorted(Xk);
    if (projected.x() < radius + 10 || projected.y() < radius + 10 ||
        projected.x() > gray.cols - radius - 10 || projected.y() > gray.rows - radius - 10)
      continue;
    // The fronto-parallel plane (reference's frame) through the point, reference -> frame k.
    const RigidPose T_rk = T_k * T_r.inverse();
    const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
    const Eigen::Matrix3d H =
        K * (T_rk.rotation() + T_rk.translation() * n.transpose() / n.dot(Xr)) * Kinv;
    const Eigen::Vector2d pr = camera.project(Xr);
    const Eigen::Vector3d q = H * pr.homogeneous();
    const Eigen::Vector2d image = q.head<2>() / q.z();
    // Frame k offsets -> reference offsets: the inverse of the Jacobian at the point.
    const Eigen::Matrix2d J = (H.topLeftCorner<2, 2>() - image * H.block<1, 2>(2, 0)) / q.z();
    const NccPatches reference = NccPatches::warped(refGray[static_cast<std::size_t>(p.view)],
                                                    {p.pixel}, {cv::Matx22f::eye()}, kHalfWindow);
    if (!reference.valid(0)) continue;
    std::vector<cv::Point2f> centres;
    for (int dy = -radius; dy <= radius; ++dy)
      for (int dx = -radius; dx <= radius; ++dx)
        centres.emplace_back(static_cast<float>(projected.x() + dx),
                             static_cast<float>(projected.y() + dy));
    const cv::Matx22f map(static_cast<float>(J(0, 0)), static_cast<float>(J(0, 1)),
                          static_cast<float>(J(1, 0)), static_cast<float>(J(1, 1)));
    const NccPatches windows = NccPatches::warped(
        gray, centres, std::vector<cv::Matx22f>(centres.size(), map), kHalfWindow);
    const int side = 2 * radius + 1;
    int best = 0;
    std::vector<double> s(centres.size());
    for (int i = 0; i < static_cast<int>(centres.size()); ++i) {
      s[static_cast<std::size_t>(i)] = reference.score(0, windows, i);
      if (s[static_cast<std::size_t>(i)] > s[static_cast<std::size_t>(best)]) best = i;
    }
    const int bx = best % side, by = best / side;
    if (s[static_cast<std::size_t>(best)] < minScore || bx == 0 || by == 0 || bx == side - 1 ||
        by == side - 1) {
      ++missed;
      continue;
    }
    const auto vertex = [](double minus, double mid, double plus) {
      const double c = minus - 2.0 * mid + plus;
      return c < 0.0 ? 0.5 * (minus - plus) / c : 0.0;
    };
    const auto at = [&](int x, int y) { return s[static_cast<std::size_t>(y * side + x)]; };
    const double ox = bx - radius + vertex(at(bx - 1, by), at(bx, by), at(bx + 1, by));
    const double oy = by - radius + vertex(at(bx, by - 1), at(bx, by), at(bx, by + 1));
    offsets.push_back(std::hypot(ox, oy));
  }
  return offsets;
}

// 4. The tracker (default parameters, the map above) run over the frames in order up to the last
// check frame; at each check frame, its inlier measurements against the truth: the frame corner of
// each inlier with a map point against that point's projection under the true pose (what the
// measurement gets wrong whatever the estimator does) and under the tracker's pose (its residual).
void reportTrackerMeasurements(const GroundTruthSequence& seq, const MultiReferenceMap& map,
                               const std::vector<int>& checkFrames) {
  const PinholeCamera& camera = seq.camera;
  const int last = *std::max_element(checkFrames.begin(), checkFrames.end());
  // Each view's corners that carry a map point, with that point (the inliers name reference corners
  // by their pixel).
  std::vector<std::vector<std::pair<cv::Point2f, const MapPoint*>>> pointsOfView(map.views.size());
  for (const MapPoint& p : map.points)
    for (const PointObservation& ob : p.observations)
      pointsOfView[static_cast<std::size_t>(ob.view)].emplace_back(
          map.views[static_cast<std::size_t>(ob.view)]
              .corners[static_cast<std::size_t>(ob.corner)]
              .pixel,
          &p);
  MultiReferenceTracker tracker(map, TrackerParams{});
  std::printf(
      "the tracker (default parameters) over frames 0-%d in order; its inliers' frame corners "
      "against their map points' projections at each check frame:\n",
      last);
  for (int k = 0; k <= last; ++k) {
    const MultiReferenceResult m = tracker.process(seq.frames[static_cast<std::size_t>(k)]);
    if (std::find(checkFrames.begin(), checkFrames.end(), k) == checkFrames.end()) continue;
    const PoseTrackingResult& r = m.tracking;
    const std::optional<RigidPose>& truth = seq.truth[static_cast<std::size_t>(k)];
    if (r.state != TrackingState::Tracking || !r.worldToCamera || !truth) {
      std::printf("frame %d: no pose (%s)\n", k, r.message.c_str());
      continue;
    }
    struct Measured {
      double toTruth, toEstimate;
      cv::Point2f pixel;
      char side;
    };
    std::vector<Measured> measured;
    int withoutPoint = 0;
    const auto collect = [&](int view, const std::vector<std::pair<cv::Point2f, cv::Point2f>>& in,
                             char side) {
      for (const auto& [framePixel, referencePixel] : in) {
        const MapPoint* found = nullptr;
        for (const auto& [c, p] : pointsOfView[static_cast<std::size_t>(view)])
          if (std::hypot(c.x - referencePixel.x, c.y - referencePixel.y) < 1e-3) {
            found = p;
            break;
          }
        if (!found) {
          ++withoutPoint;
          continue;
        }
        const Eigen::Vector2d f(framePixel.x, framePixel.y);
        measured.push_back({(f - camera.projectDistorted(*truth * found->world)).norm(),
                            (f - camera.projectDistorted(*r.worldToCamera * found->world)).norm(),
                            framePixel, side});
      }
    };
    collect(m.referenceA, r.inliersA, 'A');
    collect(m.referenceB, r.inliersB, 'B');
    std::vector<double> toTruth, toEstimate;
    for (const Measured& d : measured) {
      toTruth.push_back(d.toTruth);
      toEstimate.push_back(d.toEstimate);
    }
    // How far the tracker's pose moves the map's points from where the truth puts them.
    std::vector<double> poseShift;
    for (const MapPoint& p : map.points) {
      const Eigen::Vector3d a = *truth * p.world, b = *r.worldToCamera * p.world;
      if (a.z() > 0 && b.z() > 0)
        poseShift.push_back((camera.projectDistorted(a) - camera.projectDistorted(b)).norm());
    }
    std::printf(
        "frame %d: %zu inliers with a map point (%d without); corner to true projection median "
        "%.2f px, p90 %.2f, > 1 px %.0f, > 2 px %.0f; to the tracker's projection median %.2f; the "
        "tracker's pose moves the map points a median %.2f px from the truth\n",
        k, measured.size(), withoutPoint, quantile(toTruth, 0.5), quantile(toTruth, 0.9),
        static_cast<double>(measured.size()) * (1.0 - shareBelow(toTruth, 1.0)),
        static_cast<double>(measured.size()) * (1.0 - shareBelow(toTruth, 2.0)),
        quantile(toEstimate, 0.5), quantile(poseShift, 0.5));
    std::sort(measured.begin(), measured.end(),
              [](const Measured& a, const Measured& b) { return a.toTruth > b.toTruth; });
    for (std::size_t i = 0; i < measured.size() && i < 4 && measured[i].toTruth > 1.0; ++i)
      std::printf(
          "  off the truth: corner (%.1f, %.1f) to reference %c, %.2f px (%.2f px from the "
          "tracker's projection)\n",
          measured[i].pixel.x, measured[i].pixel.y, measured[i].side, measured[i].toTruth,
          measured[i].toEstimate);
  }
}

}  // namespace

void runReferencePairExperiment(const ReferencePairExperimentOptions& o) {
  GroundTruthSequenceSpec spec = o.sequence;
  int last = std::max(o.refA, o.refB);
  for (int k : o.checkFrames) last = std::max(last, k);
  spec.frames = last + 1;
  const GroundTruthSequence seq = loadGroundTruthSequence(spec);
  const auto frameAt = [&](int k) {
    if (k < 0 || k >= static_cast<int>(seq.frames.size()))
      throw Error("experiment-reference-pair: no frame " + std::to_string(k));
    if (!seq.truth[static_cast<std::size_t>(k)])
      throw Error("experiment-reference-pair: frame " + std::to_string(k) + " has no true pose");
    return std::make_pair(toGray8(seq.frames[static_cast<std::size_t>(k)]),
                          *seq.truth[static_cast<std::size_t>(k)]);
  };
  const auto [grayA, T_A] = frameAt(o.refA);
  const auto [grayB, T_B] = frameAt(o.refB);
  const PinholeCamera& camera = seq.camera;
  const RigidPose T_AB = T_B * T_A.inverse();
  const double viewAngle =
      std::acos(std::clamp(T_A.rotation().row(2).dot(T_B.rotation().row(2)), -1.0, 1.0)) * kDeg;
  std::printf(
      "references %d and %d: baseline %.1f mm, view angle %.1f deg, relative rotation %.2f deg\n",
      o.refA, o.refB, 1000.0 * T_AB.translation().norm(), viewAngle,
      Eigen::AngleAxisd(T_AB.rotation()).angle() * kDeg);

  // 1. The given poses against the images.
  std::vector<cv::Point2f> siftA, siftB;
  siftMatches(grayA, grayB, siftA, siftB);
  const std::vector<cv::Point2f> uA = camera.undistortPixels(siftA),
                                 uB = camera.undistortPixels(siftB);
  const Eigen::Matrix3d F = fundamentalMatrix(camera.K(), T_AB);
  std::vector<double> given;
  int farOff = 0;
  for (std::size_t i = 0; i < uA.size(); ++i) {
    const double d = epipolarDistance(F, uA[i], uB[i]);
    if (d < 20.0)
      given.push_back(d);
    else
      ++farOff;
  }
  std::printf(
      "SIFT ratio-test matches (mutual): %zu (%d more than 20 px off the given epipolar line)\n",
      uA.size(), farOff);
  printDistribution("epipolar distance under the given poses", given);
  std::vector<CheckedPoint> siftPoints;
  if (uA.size() >= 8) {
    cv::Mat inliers;
    const cv::Mat E =
        cv::findEssentialMat(uA, uB, cv::Mat(camera.Kcv()), cv::RANSAC, 0.999, 1.0, inliers);
    if (E.rows == 3 && E.cols == 3) {
      cv::Mat R, t;
      cv::recoverPose(E, uA, uB, cv::Mat(camera.Kcv()), R, t, inliers);
      Eigen::Matrix3d Re;
      Eigen::Vector3d te;
      for (int r = 0; r < 3; ++r) {
        te(r) = t.at<double>(r);
        for (int c = 0; c < 3; ++c) Re(r, c) = R.at<double>(r, c);
      }
      const RigidPose imagePose(Re, te * T_AB.translation().norm());
      const Eigen::Matrix3d Fi = fundamentalMatrix(camera.K(), imagePose);
      std::vector<double> dGiven, dImage;
      for (int i = 0; i < inliers.rows; ++i) {
        if (!inliers.at<uchar>(i)) continue;
        dGiven.push_back(
            epipolarDistance(F, uA[static_cast<std::size_t>(i)], uB[static_cast<std::size_t>(i)]));
        dImage.push_back(
            epipolarDistance(Fi, uA[static_cast<std::size_t>(i)], uB[static_cast<std::size_t>(i)]));
      }
      std::printf(
          "relative pose from the images (essential matrix, RANSAC 1 px): %zu inliers; it differs "
          "from the given one by %.2f deg of rotation and %.2f deg of translation direction\n",
          dImage.size(), Eigen::AngleAxisd(Re * T_AB.rotation().transpose()).angle() * kDeg,
          std::acos(std::clamp(te.normalized().dot(T_AB.translation().normalized()), -1.0, 1.0)) *
              kDeg);
      printDistribution("its inliers, epipolar distance under the given poses", dGiven);
      printDistribution("its inliers, epipolar distance under the images' pose", dImage);
      // The SIFT inliers triangulated with the given poses: the truth's own level in the check.
      const TwoViewTriangulator triangulator(camera.K(), T_AB);
      const RigidPose AtoWorld = T_A.inverse();
      for (int i = 0; i < inliers.rows; ++i) {
        if (!inliers.at<uchar>(i)) continue;
        const Eigen::Vector2d a(uA[static_cast<std::size_t>(i)].x,
                                uA[static_cast<std::size_t>(i)].y),
            b(uB[static_cast<std::size_t>(i)].x, uB[static_cast<std::size_t>(i)].y);
        const Eigen::Vector3d P = triangulator.refine(a, b, triangulator.linear(a, b));
        if (!P.allFinite() || P.z() <= 0.05 || (T_AB * P).z() <= 0.05 ||
            triangulator.parallaxAngle(P) < 1.0 / kDeg)
          continue;
        siftPoints.push_back({AtoWorld * P, 0, siftA[static_cast<std::size_t>(i)]});
      }
    }
  }

  // 2. The map `prepare` builds (kept whatever its size: minMatches 0).
  ReferencePreparerParams params = o.prepare;
  params.minMatches = 0;
  const double t0 = threadCpuMs();
  const MultiPreparation prepared =
      MultiReferencePreparer(camera, params)
          .prepare(
              {{seq.frames[static_cast<std::size_t>(o.refA)], "frame " + std::to_string(o.refA)},
               {seq.frames[static_cast<std::size_t>(o.refB)], "frame " + std::to_string(o.refB)}},
              std::vector<RigidPose>{T_A, T_B}, "ground truth");
  const double ms = threadCpuMs() - t0;
  const MultiReferenceMap& map = prepared.map;
  for (const ReferencePairReport& r : prepared.report.pairs) {
    const EpipolarMatchStats& s = r.matching;
    std::printf(
        "prepare: %d + %d corners, %d candidate pairs, %d mutual, kept %d (RMS %.3f px); dropped "
        "%d ambiguous, %d peak off the corner, %d behind, %d depth, %d parallax, %d reprojection, "
        "%d look-alike on the line\n",
        s.cornersA, s.cornersB, s.candidatePairs, s.mutualMatches, s.kept, s.reprojectionRmsPx,
        s.droppedAmbiguous, s.droppedPeakOffset, s.droppedBehindCamera, s.droppedOutsideDepthRange,
        s.droppedLowParallax, s.droppedReprojection, s.droppedLineRival);
    if (s.poseFit)
      std::printf(
          "  probe: %d pairs, %d fit the images' pose (rotation %.2f deg, translation direction "
          "%.2f deg from the given); median / p90 distance to the lines: given %.2f / %.2f px, "
          "images' %.2f / %.2f px: %s\n",
          s.probeMatches, s.poseFit->inliers, s.poseFit->rotationChangeDeg,
          s.poseFit->translationDirectionChangeDeg, s.poseFit->givenMedianPx, s.poseFit->givenP90Px,
          s.poseFit->fittedMedianPx, s.poseFit->fittedP90Px,
          s.posesDisagree ? "disagree" : "agree");
    else
      std::printf("  probe: %d pairs (no fit)\n", s.probeMatches);
  }
  if (prepared.report.poseRefinement) {
    const ReferencePoseRefinement& r = *prepared.report.poseRefinement;
    std::printf(
        "  reference poses refined: RMS %.3f -> %.3f px, reference 1 moved %.2f mm, %.3f deg\n",
        r.initialRmsPx, r.finalRmsPx, r.movedMillimetres.back(), r.movedDeg.back());
  }
  std::printf("map points: %zu; preparation %.0f ms thread CPU (keypoint layer included)\n",
              map.points.size(), ms);

  // 3. The map's points (and the SIFT points) in other frames with true poses.
  std::vector<CheckedPoint> mapPoints;
  for (const MapPoint& p : map.points) {
    const PointObservation& first = p.observations.front();
    mapPoints.push_back({p.world, first.view, map.measuredPixel(first)});
  }
  const std::vector<cv::Mat> refGray = {grayA, grayB};
  const std::vector<RigidPose> refPose = {map.views[0].T, map.views[1].T};
  const std::vector<RigidPose> givenPose = {T_A, T_B};
  std::vector<double> allMap, allSift;
  int missedMap = 0, missedSift = 0;
  for (int k : o.checkFrames) {
    const auto [gray, T_k] = frameAt(k);
    int mm = 0, ms2 = 0;
    const std::vector<double> dm = offsetsInFrame(camera, refGray, refPose, mapPoints, gray, T_k,
                                                  o.searchRadiusPx, o.minScore, mm);
    const std::vector<double> ds = offsetsInFrame(camera, refGray, givenPose, siftPoints, gray, T_k,
                                                  o.searchRadiusPx, o.minScore, ms2);
    std::printf(
        "frame %d: map points found %zu (missed %d), median %.2f px, p90 %.2f, > 5 px %.0f%%; SIFT "
        "points found %zu (missed %d), median %.2f px, p90 %.2f, > 5 px %.0f%%\n",
        k, dm.size(), mm, quantile(dm, 0.5), quantile(dm, 0.9), 100.0 * (1.0 - shareBelow(dm, 5.0)),
        ds.size(), ms2, quantile(ds, 0.5), quantile(ds, 0.9), 100.0 * (1.0 - shareBelow(ds, 5.0)));
    allMap.insert(allMap.end(), dm.begin(), dm.end());
    allSift.insert(allSift.end(), ds.begin(), ds.end());
    missedMap += mm;
    missedSift += ms2;
  }
  if (!o.checkFrames.empty()) {
    std::printf("all check frames: map points (%d missed)\n", missedMap);
    printDistribution("offset of the map points' peaks from their projections", allMap);
    std::printf("  > 5 px: %.1f%%\n", 100.0 * (1.0 - shareBelow(allMap, 5.0)));
    std::printf("all check frames: SIFT points (%zu points, %d missed)\n", siftPoints.size(),
                missedSift);
    printDistribution("offset of the SIFT points' peaks from their projections", allSift);
    std::printf("  > 5 px: %.1f%%\n", 100.0 * (1.0 - shareBelow(allSift, 5.0)));
    reportTrackerMeasurements(seq, map, o.checkFrames);
  }
}

}  // namespace reftrack::app
