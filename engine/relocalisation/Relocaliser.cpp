#include "engine/relocalisation/Relocaliser.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/core/ThreadCpuClock.hpp"
#include "engine/features/CornerGrid.hpp"
#include "engine/relocalisation/KeypointFeatures.hpp"

namespace reftrack {

namespace {

// Retrieval votes with the strongest this many frame keypoints only: enough to rank the
// references (each gets its ratio-test match count), a quarter of the cost of matching all.
constexpr int kRetrievalKeypoints = 250;
// The inlier spread is counted on a kSpreadGrid x kSpreadGrid grid over the frame.
constexpr int kSpreadGrid = 4;
// A far view's mapped region is detected again magnified by up to kMaxZoom (2x: a reference's
// finest keypoints seen from twice its distance), when that is at least kMinZoom.
constexpr double kMaxZoom = 2.0, kMinZoom = 1.2;

// A pixel of an image region at `origin` magnified `zoom` times with cv::resize, in the frame
// (cv::resize maps pixel centres: x_src = (x_dst + 0.5) / zoom - 0.5).
cv::Point2f magnifiedToFrame(cv::Point2f p, double zoom, cv::Point origin) {
  return {static_cast<float>((p.x + 0.5) / zoom - 0.5 + origin.x),
          static_cast<float>((p.y + 0.5) / zoom - 0.5 + origin.y)};
}

struct IndexedReference {
  int view = -1;
  cv::Mat descriptors;              // rows of the keypoints that have a 3D point
  std::vector<cv::Point3f> points;  // their world points
};

// Megapixels a keypoint detection works on: the image reduced by `scale`; ORB's finer levels
// above it (upsampled 1.2x each) add their areas.
double detectedMegapixels(cv::Size image, double scale, int finerLevels = 0) {
  double levels = 1.0, level = 1.0;
  for (int l = 0; l < finerLevels; ++l) levels += (level *= 1.44);
  return 1e-6 * static_cast<double>(image.area()) * scale * scale * levels;
}

// Descriptor distances of a brute-force match of `query` rows against `train` rows, in millions.
double comparisonsMillions(const cv::Mat& query, const cv::Mat& train) {
  return 1e-6 * static_cast<double>(query.rows) * static_cast<double>(train.rows);
}

RigidPose poseFrom(const cv::Mat& rvec, const cv::Mat& tvec) {
  Vector6d x;
  x << tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2), rvec.at<double>(0),
      rvec.at<double>(1), rvec.at<double>(2);
  return RigidPose::fromVector6(x);
}

// How well the inliers pin the pose down: the standard deviations of the pose from the
// Gauss-Newton covariance sigma^2 (J^T J)^-1 of the reprojection residuals (J over rvec, tvec),
// with sigma the inliers' residual RMS (at least 1 px: keypoints are no better located). A pose
// held up by a small, distant patch of the scene has a large one even with many inliers.
struct PoseSpread {
  double rotationDeg = 0.0;        // largest rotation standard deviation
  double positionOverDepth = 0.0;  // largest translation standard deviation / median depth
};

PoseSpread poseSpread(const std::vector<cv::Point3f>& object, const std::vector<cv::Point2f>& image,
                      const std::vector<int>& inliers, const cv::Mat& rvec, const cv::Mat& tvec,
                      const cv::Mat& K, const cv::Mat& distortion) {
  PoseSpread out;
  if (inliers.size() < 4) return {1e9, 1e9};
  std::vector<cv::Point3f> obj;
  std::vector<cv::Point2f> img;
  for (int i : inliers) {
    obj.push_back(object[static_cast<std::size_t>(i)]);
    img.push_back(image[static_cast<std::size_t>(i)]);
  }
  std::vector<cv::Point2f> back;
  cv::Mat J;
  cv::projectPoints(obj, rvec, tvec, K, distortion, back, J);
  double sum2 = 0.0;
  for (std::size_t i = 0; i < img.size(); ++i) sum2 += std::pow(cv::norm(back[i] - img[i]), 2);
  const double sigma = std::max(1.0, std::sqrt(sum2 / static_cast<double>(img.size())));
  const cv::Mat Jpose = J.colRange(0, 6);
  cv::Mat covariance;
  if (cv::invert(Jpose.t() * Jpose, covariance, cv::DECOMP_SVD) == 0) return {1e9, 1e9};
  covariance *= sigma * sigma;
  cv::Mat eigen;
  cv::eigen(covariance(cv::Range(0, 3), cv::Range(0, 3)), eigen);
  out.rotationDeg = std::sqrt(std::max(0.0, eigen.at<double>(0))) * 180.0 / M_PI;
  cv::eigen(covariance(cv::Range(3, 6), cv::Range(3, 6)), eigen);
  cv::Mat R;
  cv::Rodrigues(rvec, R);
  std::vector<double> depth;
  for (const cv::Point3f& X : obj)
    depth.push_back(R.at<double>(2, 0) * X.x + R.at<double>(2, 1) * X.y + R.at<double>(2, 2) * X.z +
                    tvec.at<double>(2));
  std::nth_element(depth.begin(), depth.begin() + static_cast<long>(depth.size() / 2), depth.end());
  const double medianDepth = depth[depth.size() / 2];
  out.positionOverDepth =
      medianDepth > 0 ? std::sqrt(std::max(0.0, eigen.at<double>(0))) / medianDepth : 1e9;
  return out;
}

}  // namespace

struct Relocaliser::Impl {
  RelocalisationParams params;
  PinholeCamera camera;
  KeypointFeatures features;
  std::vector<IndexedReference> references;
  cv::Mat K, distortion;

  Impl(const MultiReferenceMap& map, const RelocalisationParams& p)
      : params(p), camera(map.camera), features(p.keypoints) {}
  // The frame's detection scale: relocalisation.sift_frame_scale for SIFT, full size otherwise.
  double frameScale() const { return params.keypoints == "sift" ? params.siftFrameScale : 1.0; }

  struct Match {
    int reference = -1;  // index into references
    int point = -1;
    float distance = 0.0f;
  };

  // The references to match: all when there are few, else the best-voted ones.
  std::vector<int> retrieve(const std::vector<cv::KeyPoint>& keypoints, const cv::Mat& descriptors,
                            KeypointWork& work) const;
  RelocalisationAttempt locate(const cv::Mat& frame, double scale) const;
  void checkFrame(const cv::Mat& frame) const;
  KeypointSupport ratioTestSupport(const cv::Mat& frame, const RigidPose& worldToCamera) const;
  int agreeing(const RigidPose& worldToCamera, const std::vector<cv::Point3f>& points,
               const std::vector<cv::Point2f>& pixels, double thresholdScale = 1.0) const;
  // Per frame keypoint: its closest ratio-test match over the references `matched` (indices into
  // references), or reference -1. Every call counts what it did into `work` (KeypointWork).
  std::vector<Match> bestMatches(const cv::Mat& descriptors, std::size_t keypoints,
                                 const std::vector<int>& matched, KeypointWork& work) const;
  // The pose from the frame's keypoints matched to the references `matched` (indices into
  // references), guided matching and the acceptance; the first inliers must be at least
  // `minInlierRatio` of the matches.
  RelocalisationAttempt locateWith(const cv::Mat& frame, const std::vector<cv::KeyPoint>& keypoints,
                                   const cv::Mat& descriptors, const std::vector<int>& matched,
                                   double minInlierRatio) const;
  // LM refinement on `inliers`, twice re-selecting the matches within `threshold` px (in front
  // of the camera) under the refined pose; `errors` gets every match's reprojection error.
  void refine(const std::vector<cv::Point3f>& object, const std::vector<cv::Point2f>& image,
              double threshold, cv::Mat& rvec, cv::Mat& tvec, std::vector<int>& inliers,
              std::vector<double>& errors) const;
  // Appends to object/image/matchReference the frame keypoints (other than the `used` ones)
  // that lie within `radius` px of a reference point projected with rvec/tvec and whose
  // descriptor is within `maxDistance` of that point's: the closest such point each.
  void guidedMatches(const std::vector<cv::KeyPoint>& keypoints, const cv::Mat& descriptors,
                     const cv::Mat& rvec, const cv::Mat& tvec, double radius, float maxDistance,
                     const std::vector<char>& used, std::vector<cv::Point3f>& object,
                     std::vector<cv::Point2f>& image, std::vector<int>& matchReference,
                     KeypointWork& work) const;
};

Relocaliser::Relocaliser(const MultiReferenceMap& map, const RelocalisationParams& params) {
  params.check();
  impl_ = std::make_unique<Impl>(map, params);
  if (map.keypointKind.empty())
    throw Error("relocalisation: the map has no keypoint layer (prepare it again)");
  if (map.keypointKind != params.keypoints)
    throw Error("relocalisation: the map's keypoints are '" + map.keypointKind +
                "' but relocalisation.keypoints is '" + params.keypoints +
                "' (prepare the map again with these parameters)");
  for (int v = 0; v < map.size(); ++v) {
    const ReferenceKeypoints& layer = map.views[static_cast<std::size_t>(v)].keypoints;
    layer.check("views[" + std::to_string(v) + "].keypoints");
    IndexedReference r;
    r.view = v;
    for (std::size_t k = 0; k < layer.keypoints.size(); ++k) {
      if (!layer.points[k].allFinite()) continue;
      r.descriptors.push_back(layer.descriptors.row(static_cast<int>(k)));
      r.points.emplace_back(static_cast<float>(layer.points[k].x()),
                            static_cast<float>(layer.points[k].y()),
                            static_cast<float>(layer.points[k].z()));
    }
    if (static_cast<int>(r.points.size()) >= params.minInliers)
      impl_->references.push_back(std::move(r));
  }
  if (impl_->references.empty())
    throw Error("relocalisation: no reference of the map has a keypoint layer with " +
                std::to_string(params.minInliers) + " or more 3D points");
  cv::Mat(camera().Kcv()).copyTo(impl_->K);
  impl_->distortion = cv::Mat(impl_->camera.distortion(), true);
}

Relocaliser::~Relocaliser() = default;

const PinholeCamera& Relocaliser::camera() const { return impl_->camera; }

KeypointSupport Relocaliser::ratioTestSupport(const cv::Mat& frame,
                                              const RigidPose& worldToCamera) const {
  return impl_->ratioTestSupport(frame, worldToCamera);
}

int Relocaliser::agreeing(const RigidPose& worldToCamera, const std::vector<cv::Point3f>& points,
                          const std::vector<cv::Point2f>& pixels, double thresholdScale) const {
  return impl_->agreeing(worldToCamera, points, pixels, thresholdScale);
}

RelocalisationAttempt Relocaliser::locate(const cv::Mat& frame, bool fullResolution) const {
  const auto start = std::chrono::steady_clock::now();
  const double cpuStart = processCpuMs();
  RelocalisationAttempt attempt = impl_->locate(frame, fullResolution ? 1.0 : impl_->frameScale());
  attempt.cpuMs = processCpuMs() - cpuStart;
  attempt.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return attempt;
}

std::vector<int> Relocaliser::Impl::retrieve(const std::vector<cv::KeyPoint>& keypoints,
                                             const cv::Mat& descriptors, KeypointWork& work) const {
  std::vector<int> all(references.size());
  std::iota(all.begin(), all.end(), 0);
  if (static_cast<int>(references.size()) <= params.referencesToMatch) return all;
  // The strongest frame keypoints vote: a reference scores its ratio-test matches.
  std::vector<int> order(keypoints.size());
  std::iota(order.begin(), order.end(), 0);
  const std::size_t voters = std::min<std::size_t>(order.size(), kRetrievalKeypoints);
  std::partial_sort(order.begin(), order.begin() + static_cast<long>(voters), order.end(),
                    [&](int a, int b) {
                      return keypoints[static_cast<std::size_t>(a)].response >
                             keypoints[static_cast<std::size_t>(b)].response;
                    });
  cv::Mat voting;
  for (std::size_t i = 0; i < voters; ++i) voting.push_back(descriptors.row(order[i]));
  std::vector<std::size_t> votes(references.size(), 0);
  for (std::size_t r = 0; r < references.size(); ++r) {
    votes[r] = matchDescriptors(voting, references[r].descriptors, features.normType(),
                                params.ratio, false)
                   .size();
    work.comparisonsMillions += comparisonsMillions(voting, references[r].descriptors);
  }
  std::stable_sort(all.begin(), all.end(), [&](int a, int b) {
    return votes[static_cast<std::size_t>(a)] > votes[static_cast<std::size_t>(b)];
  });
  all.resize(static_cast<std::size_t>(params.referencesToMatch));
  return all;
}

void Relocaliser::Impl::refine(const std::vector<cv::Point3f>& object,
                               const std::vector<cv::Point2f>& image, double threshold,
                               cv::Mat& rvec, cv::Mat& tvec, std::vector<int>& inliers,
                               std::vector<double>& errors) const {
  errors.assign(object.size(), 1e9);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<cv::Point3f> obj;
    std::vector<cv::Point2f> img;
    for (int i : inliers) {
      obj.push_back(object[static_cast<std::size_t>(i)]);
      img.push_back(image[static_cast<std::size_t>(i)]);
    }
    cv::solvePnPRefineLM(obj, img, K, distortion, rvec, tvec);
    std::vector<cv::Point2f> back;
    cv::projectPoints(object, rvec, tvec, K, distortion, back);
    const RigidPose T = poseFrom(rvec, tvec);
    inliers.clear();
    for (std::size_t i = 0; i < object.size(); ++i) {
      const Eigen::Vector3d X(object[i].x, object[i].y, object[i].z);
      errors[i] = (T * X).z() > 0 ? cv::norm(back[i] - image[i]) : 1e9;
      if (errors[i] < threshold) inliers.push_back(static_cast<int>(i));
    }
    if (static_cast<int>(inliers.size()) < params.minInliers) break;
  }
}

void Relocaliser::Impl::guidedMatches(const std::vector<cv::KeyPoint>& keypoints,
                                      const cv::Mat& descriptors, const cv::Mat& rvec,
                                      const cv::Mat& tvec, double radius, float maxDistance,
                                      const std::vector<char>& used,
                                      std::vector<cv::Point3f>& object,
                                      std::vector<cv::Point2f>& image,
                                      std::vector<int>& matchReference, KeypointWork& work) const {
  // The unused frame keypoints on a grid of `radius` cells (CornerGrid: one contiguous array,
  // where a vector per cell cost a heap allocation per keypoint on every attempt).
  const cv::Size size = camera.imageSize();
  std::vector<cv::Point2f> free;
  std::vector<int> freeKeypoint;
  for (std::size_t k = 0; k < keypoints.size(); ++k) {
    if (used[k]) continue;
    free.push_back(keypoints[k].pt);
    freeKeypoint.push_back(static_cast<int>(k));
  }
  const CornerGrid grid(free, size, std::max(1, static_cast<int>(std::ceil(radius))));
  std::vector<int> nearby;
  struct Guided {
    int reference = -1, point = -1;
    double distance = 0.0;
  };
  std::vector<Guided> best(keypoints.size());
  cv::Mat R;
  cv::Rodrigues(rvec, R);
  const double r2 = radius * radius;
  long long distances = 0;
  for (std::size_t r = 0; r < references.size(); ++r) {
    const IndexedReference& ref = references[r];
    std::vector<cv::Point2f> projected;
    cv::projectPoints(ref.points, rvec, tvec, K, distortion, projected);
    for (std::size_t p = 0; p < ref.points.size(); ++p) {
      const cv::Point3f& X = ref.points[p];
      const double z = R.at<double>(2, 0) * X.x + R.at<double>(2, 1) * X.y +
                       R.at<double>(2, 2) * X.z + tvec.at<double>(2);
      const cv::Point2f& u = projected[p];
      if (!(z > 0) || !(u.x >= 0 && u.y >= 0 && u.x < size.width && u.y < size.height)) continue;
      grid.query(cv::Point2d(u), radius, radius, nearby);
      for (const int f : nearby) {
        const int k = freeKeypoint[static_cast<std::size_t>(f)];
        const cv::Point2f d = keypoints[static_cast<std::size_t>(k)].pt - u;
        if (d.x * d.x + d.y * d.y > r2) continue;
        // descriptorDistance, not cv::norm: this Debian OpenCV's Hamming norm has no
        // hardware popcount; measured 6.7 -> 2.7 ms of guided matching per attempt.
        const double distance = descriptorDistance(descriptors, k, ref.descriptors,
                                                   static_cast<int>(p), features.normType());
        ++distances;
        Guided& b = best[static_cast<std::size_t>(k)];
        if (distance <= maxDistance && (b.reference < 0 || distance < b.distance))
          b = {static_cast<int>(r), static_cast<int>(p), distance};
      }
    }
  }
  work.comparisonsMillions += 1e-6 * static_cast<double>(distances);
  for (std::size_t k = 0; k < best.size(); ++k) {
    if (best[k].reference < 0) continue;
    object.push_back(references[static_cast<std::size_t>(best[k].reference)]
                         .points[static_cast<std::size_t>(best[k].point)]);
    image.push_back(keypoints[k].pt);
    matchReference.push_back(best[k].reference);
  }
}

void Relocaliser::Impl::checkFrame(const cv::Mat& frame) const {
  const cv::Size size = camera.imageSize();
  if (frame.empty()) throw Error("relocalisation: empty frame");
  if (frame.size() != size)
    throw Error("relocalisation: frame is " + std::to_string(frame.cols) + "x" +
                std::to_string(frame.rows) + " but the map's camera is " +
                std::to_string(size.width) + "x" + std::to_string(size.height));
  if (frame.depth() != CV_8U || (frame.channels() != 1 && frame.channels() != 3))
    throw Error("relocalisation: frame must be 8-bit grey or BGR");
}

std::vector<Relocaliser::Impl::Match> Relocaliser::Impl::bestMatches(
    const cv::Mat& descriptors, std::size_t keypoints, const std::vector<int>& matched,
    KeypointWork& work) const {
  std::vector<Match> best(keypoints);
  for (int r : matched) {
    work.comparisonsMillions +=
        comparisonsMillions(descriptors, references[static_cast<std::size_t>(r)].descriptors);
    for (const cv::DMatch& m :
         matchDescriptors(descriptors, references[static_cast<std::size_t>(r)].descriptors,
                          features.normType(), params.ratio, false)) {
      Match& b = best[static_cast<std::size_t>(m.queryIdx)];
      if (b.reference < 0 || m.distance < b.distance) b = {r, m.trainIdx, m.distance};
    }
  }
  return best;
}

int Relocaliser::Impl::agreeing(const RigidPose& worldToCamera,
                                const std::vector<cv::Point3f>& points,
                                const std::vector<cv::Point2f>& pixels,
                                double thresholdScale) const {
  const double threshold =
      thresholdScale * params.reprojectionPx * resolutionScale(camera.imageSize());
  int n = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d Xc =
        worldToCamera * Eigen::Vector3d(points[i].x, points[i].y, points[i].z);
    if (Xc.z() <= 0) continue;
    const Eigen::Vector2d p = camera.projectDistorted(Xc);
    n += std::hypot(p.x() - pixels[i].x, p.y() - pixels[i].y) < threshold;
  }
  return n;
}

KeypointSupport Relocaliser::Impl::ratioTestSupport(const cv::Mat& frame,
                                                    const RigidPose& worldToCamera) const {
  checkFrame(frame);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  features.detectAndDescribe(frame, params.featuresPerFrameFor(camera.imageSize()), keypoints,
                             descriptors, 0, 0, frameScale());
  KeypointSupport support;
  support.work.detectedMegapixels = detectedMegapixels(frame.size(), frameScale());
  std::vector<int> all(references.size());
  std::iota(all.begin(), all.end(), 0);
  const std::vector<Match> best = bestMatches(descriptors, keypoints.size(), all, support.work);
  std::vector<cv::Point3f> points;
  std::vector<cv::Point2f> pixels;
  for (std::size_t k = 0; k < best.size(); ++k) {
    if (best[k].reference < 0) continue;
    points.push_back(references[static_cast<std::size_t>(best[k].reference)]
                         .points[static_cast<std::size_t>(best[k].point)]);
    pixels.push_back(keypoints[k].pt);
  }
  support.matches = static_cast<int>(points.size());
  support.agreeing = agreeing(worldToCamera, points, pixels);
  return support;
}

RelocalisationAttempt Relocaliser::Impl::locate(const cv::Mat& frame, double scale) const {
  const cv::Size size = camera.imageSize();
  checkFrame(frame);

  RelocalisationAttempt out;
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  features.detectAndDescribe(frame, params.featuresPerFrameFor(size), keypoints, descriptors, 0, 0,
                             scale);
  KeypointWork work;
  work.detectedMegapixels = detectedMegapixels(size, scale);
  if (static_cast<int>(keypoints.size()) < params.minInliers) {
    out.message = "too few keypoints (" + std::to_string(keypoints.size()) +
                  "): black, textureless or blurred frame";
    out.stop = RecoveryStage::TooFewKeypoints;
    out.work = work;
    return out;
  }
  // Every way out carries the work done up to it.
  const auto done = [&work](RelocalisationAttempt attempt) {
    attempt.work += work;
    return attempt;
  };

  // Retrieval ranks the references by the votes of the strongest keypoints; when the best-voted
  // ones give no pose, all are matched (measured on 40 random views of 8 walkaround
  // references: 3 of the 4 views the top two left without a pose were relocalised by all 8; the
  // fallback costs only on such frames, an attempt's median stays that of matching two).
  const std::vector<int> retrieved = retrieve(keypoints, descriptors, work);
  RelocalisationAttempt first =
      locateWith(frame, keypoints, descriptors, retrieved, params.minInlierRatio);
  work += first.work;
  first.work = {};
  if (first.candidate) return done(std::move(first));
  std::vector<int> all(references.size());
  std::iota(all.begin(), all.end(), 0);
  if (retrieved.size() != references.size()) {
    RelocalisationAttempt second =
        locateWith(frame, keypoints, descriptors, all, params.minInlierRatio);
    if (second.candidate) return done(std::move(second));
    work += second.work;
    first.message += "; with all references: " + second.message;
  }
  // A far view sees the references' finest keypoints below its own finest ORB scale: the frame
  // is detected again with finer (upsampled) pyramid levels and matched to every reference.
  // Only frames that gave no pose pay for it; the acceptance is the same.
  if (params.keypoints != "orb" || params.frameFinerLevels == 0) return done(std::move(first));
  std::vector<cv::KeyPoint> fine;
  cv::Mat fineDescriptors;
  features.detectAndDescribe(frame,
                             params.featuresPerFrameFor(size) * (4 + params.frameFinerLevels) / 4,
                             fine, fineDescriptors, params.frameFinerLevels);
  work.detectedMegapixels += detectedMegapixels(size, 1.0, params.frameFinerLevels);
  // Its matches come from 1 + levels/4 times the keypoints against every reference (not the two
  // retrieved): the false ones multiply, the mapped region's true ones hardly. The inlier share
  // bound is halved for it (measured on seeds 1-3 of experiment-relocalisation: the far views it
  // left without a pose had 64-161 inliers at 13-24% of ~500 matches, pose sigma <= 0.23 deg).
  RelocalisationAttempt finer =
      locateWith(frame, fine, fineDescriptors, all, 0.5 * params.minInlierRatio);
  finer.message = first.message + "; with finer frame levels: " + finer.message;
  return done(std::move(finer));
}

RelocalisationAttempt Relocaliser::Impl::locateWith(const cv::Mat& frame,
                                                    const std::vector<cv::KeyPoint>& keypoints,
                                                    const cv::Mat& descriptors,
                                                    const std::vector<int>& matched,
                                                    double minInlierRatio) const {
  const cv::Size size = camera.imageSize();
  RelocalisationAttempt out;
  // 2D-3D matches: each frame keypoint keeps its closest ratio-test match over the references.
  const std::vector<Match> best = bestMatches(descriptors, keypoints.size(), matched, out.work);
  std::vector<cv::Point3f> object;
  std::vector<cv::Point2f> image;
  std::vector<int> matchReference;
  std::vector<float> matchDistance;
  std::vector<int> matchKeypoint;
  for (std::size_t k = 0; k < best.size(); ++k) {
    if (best[k].reference < 0) continue;
    matchDistance.push_back(best[k].distance);
    matchKeypoint.push_back(static_cast<int>(k));
    object.push_back(references[static_cast<std::size_t>(best[k].reference)]
                         .points[static_cast<std::size_t>(best[k].point)]);
    image.push_back(keypoints[k].pt);
    matchReference.push_back(best[k].reference);
  }
  const int matches = static_cast<int>(object.size());
  if (matches < params.minInliers) {
    out.message = "too few matches with the map (" + std::to_string(matches) + " < " +
                  std::to_string(params.minInliers) + ")";
    out.stop = RecoveryStage::TooFewMatches;
    return out;
  }

  // PnP-RANSAC (AP3P minimal solver), then Levenberg-Marquardt on the inliers. Measured against
  // P3P, SQPnP (EPnP samples) and USAC MAGSAC++ (cv::UsacParams): the same views relocalised
  // (39/40 synthetic, 161/161 postcard) with centre errors within 0.2 mm of each other, and the
  // RANSAC stage is 0.4-6 ms of an attempt, the times of all four within the run-to-run noise.
  const double threshold = params.reprojectionPx * resolutionScale(size);
  cv::Mat rvec, tvec;
  std::vector<int> ransacInliers;
  ++out.work.poseSearches;
  const bool found =
      cv::solvePnPRansac(object, image, K, distortion, rvec, tvec, false, params.ransacIterations,
                         static_cast<float>(threshold), 0.999, ransacInliers, cv::SOLVEPNP_AP3P);
  if (!found || static_cast<int>(ransacInliers.size()) < params.minInliers) {
    out.message = "PnP-RANSAC found no pose with " + std::to_string(params.minInliers) +
                  " inliers (" + std::to_string(ransacInliers.size()) + " of " +
                  std::to_string(matches) + " matches)";
    out.stop = RecoveryStage::PnpInliers;
    return out;
  }
  // solvePnPRansac re-estimates the pose from the best sample's inliers with EPnP (after AP3P
  // samples), which can break down when they lie near a plane (a close view of the desk top):
  // seen as poses that kept 2 of 50+ inliers. SQPnP (globally optimal, planar or not) on the
  // same inliers replaces it when it reprojects more of them within the threshold.
  {
    std::vector<cv::Point3f> obj;
    std::vector<cv::Point2f> img;
    for (int i : ransacInliers) {
      obj.push_back(object[static_cast<std::size_t>(i)]);
      img.push_back(image[static_cast<std::size_t>(i)]);
    }
    const auto within = [&](const cv::Mat& r, const cv::Mat& t) {
      std::vector<cv::Point2f> back;
      cv::projectPoints(obj, r, t, K, distortion, back);
      int n = 0;
      for (std::size_t i = 0; i < img.size(); ++i) n += cv::norm(back[i] - img[i]) < threshold;
      return n;
    };
    const int returned = within(rvec, tvec);
    cv::Mat sr, st;
    if (returned < static_cast<int>(obj.size()) &&
        cv::solvePnP(obj, img, K, distortion, sr, st, false, cv::SOLVEPNP_SQPNP) &&
        within(sr, st) > returned) {
      rvec = sr;
      tvec = st;
    }
  }
  // Refine on the inliers, re-select the inliers under the refined pose, refine once more.
  std::vector<int> inliers = ransacInliers;
  std::vector<double> errors;
  refine(object, image, threshold, rvec, tvec, inliers, errors);
  const int firstInliers = static_cast<int>(inliers.size());
  std::vector<cv::Point3f> distinctivePoints;
  std::vector<cv::Point2f> distinctivePixels;
  for (int i : inliers) {
    distinctivePoints.push_back(object[static_cast<std::size_t>(i)]);
    distinctivePixels.push_back(image[static_cast<std::size_t>(i)]);
  }
  const double ratio = static_cast<double>(firstInliers) / matches;

  // Guided matching: a far view sees the scene small, and the ratio test against whole
  // references keeps few of its matches (on 8 walkaround references, 50-120 inliers at 1.4-1.9x
  // the reference distance: a pose spread of 0.3-0.5% of the depth, over the bound). The first
  // pose projects every reference's points into the frame; a frame keypoint near a projection
  // with a descriptor as close as the first inliers' takes it, and the pose is refined on the
  // larger set. The acceptance below then judges the pose on all its support, with the same
  // bounds.
  float guidedMaxDistance = 0.0f;
  if (firstInliers >= params.minInliers && ratio >= minInlierRatio) {
    std::vector<float> inlierDistances;
    for (int i : inliers) inlierDistances.push_back(matchDistance[static_cast<std::size_t>(i)]);
    const auto q = inlierDistances.begin() + static_cast<long>(inlierDistances.size() * 9 / 10);
    std::nth_element(inlierDistances.begin(), q, inlierDistances.end());
    guidedMaxDistance = *q;
    // The first inliers stay; the other keypoints may take a guided match.
    std::vector<cv::Point3f> guidedObject;
    std::vector<cv::Point2f> guidedImage;
    std::vector<int> guidedReference;
    std::vector<char> used(keypoints.size(), 0);
    for (int i : inliers) {
      const auto u = static_cast<std::size_t>(i);
      guidedObject.push_back(object[u]);
      guidedImage.push_back(image[u]);
      guidedReference.push_back(matchReference[u]);
      used[static_cast<std::size_t>(matchKeypoint[u])] = 1;
    }
    guidedMatches(keypoints, descriptors, rvec, tvec, 2.0 * threshold, guidedMaxDistance, used,
                  guidedObject, guidedImage, guidedReference, out.work);
    object = std::move(guidedObject);
    image = std::move(guidedImage);
    matchReference = std::move(guidedReference);
    inliers.resize(object.size());
    std::iota(inliers.begin(), inliers.end(), 0);
    refine(object, image, threshold, rvec, tvec, inliers, errors);
  }

  // Acceptance: enough inliers, a large enough share of the matches, spread over the frame.
  struct Support {
    int covered = 0;
    PoseSpread spread;
    bool enough = false;
  };
  const auto assess = [&] {
    Support sp;
    std::vector<bool> cells(kSpreadGrid * kSpreadGrid, false);
    for (int i : inliers) {
      const auto u = static_cast<std::size_t>(i);
      const int cx =
          std::clamp(static_cast<int>(image[u].x * kSpreadGrid / size.width), 0, kSpreadGrid - 1);
      const int cy =
          std::clamp(static_cast<int>(image[u].y * kSpreadGrid / size.height), 0, kSpreadGrid - 1);
      cells[static_cast<std::size_t>(cy * kSpreadGrid + cx)] = true;
    }
    sp.covered = static_cast<int>(std::count(cells.begin(), cells.end(), true));
    sp.spread = poseSpread(object, image, inliers, rvec, tvec, K, distortion);
    sp.enough = static_cast<int>(inliers.size()) >= params.minInliers &&
                sp.covered >= params.minInlierCells && poseFrom(rvec, tvec).allFinite() &&
                sp.spread.rotationDeg <= params.maxRotationSigmaDeg &&
                sp.spread.positionOverDepth <= params.maxPositionSigmaRatio;
    return sp;
  };
  const bool firstStage = firstInliers >= params.minInliers && ratio >= minInlierRatio;
  Support support = assess();
  std::string zoomText;
  // A pose right but spread too wide is a far view's: the mapped scene fills a small part of the
  // frame, and its finest map keypoints are below the frame's finest ORB scale. The region the
  // inliers cover is detected again, magnified up to kMaxZoom, and the keypoints found there are
  // matched guided by the pose (a second guided pass; the bounds unchanged).
  if (firstStage && !support.enough && !inliers.empty()) {
    std::vector<cv::Point2f> inlierPixels;
    for (int i : inliers) inlierPixels.push_back(image[static_cast<std::size_t>(i)]);
    const int margin = static_cast<int>(std::ceil(4.0 * threshold));
    const cv::Rect roi = (cv::boundingRect(inlierPixels) + cv::Size(2 * margin, 2 * margin) -
                          cv::Point(margin, margin)) &
                         cv::Rect(cv::Point(0, 0), size);
    const double zoom =
        std::min(kMaxZoom, std::sqrt(static_cast<double>(size.area()) / std::max(1, roi.area())));
    if (zoom >= kMinZoom && roi.area() > 0) {
      cv::Mat magnified;
      cv::resize(frame(roi), magnified, cv::Size(), zoom, zoom, cv::INTER_LINEAR);
      std::vector<cv::KeyPoint> zoomed;
      cv::Mat zoomedDescriptors;
      features.detectAndDescribe(magnified, params.featuresPerFrameFor(size), zoomed,
                                 zoomedDescriptors);
      out.work.detectedMegapixels += detectedMegapixels(magnified.size(), 1.0);
      for (cv::KeyPoint& k : zoomed) k.pt = magnifiedToFrame(k.pt, zoom, roi.tl());
      std::vector<cv::Point3f> zObject;
      std::vector<cv::Point2f> zImage;
      std::vector<int> zReference;
      guidedMatches(zoomed, zoomedDescriptors, rvec, tvec, 2.0 * threshold, guidedMaxDistance,
                    std::vector<char>(zoomed.size(), 0), zObject, zImage, zReference, out.work);
      if (static_cast<int>(zObject.size()) > static_cast<int>(inliers.size())) {
        cv::Mat zr = rvec.clone(), zt = tvec.clone();
        std::vector<int> zInliers(zObject.size());
        std::iota(zInliers.begin(), zInliers.end(), 0);
        std::vector<double> zErrors;
        refine(zObject, zImage, threshold, zr, zt, zInliers, zErrors);
        if (zInliers.size() > inliers.size()) {
          object = std::move(zObject);
          image = std::move(zImage);
          matchReference = std::move(zReference);
          inliers = std::move(zInliers);
          errors = std::move(zErrors);
          rvec = zr;
          tvec = zt;
          support = assess();
          char text[64];
          std::snprintf(text, sizeof text, ", frame region magnified %.1fx", zoom);
          zoomText = text;
        }
      }
    }
  }

  const int n = static_cast<int>(inliers.size());
  std::vector<int> perReference(references.size(), 0);
  double sum2 = 0.0;
  for (int i : inliers) {
    const auto u = static_cast<std::size_t>(i);
    ++perReference[static_cast<std::size_t>(matchReference[u])];
    sum2 += errors[u] * errors[u];
  }
  // poseSpread() marks a pose its inliers cannot pin down (rank-deficient, no depth) with 1e9.
  char spreadText[96];
  if (support.spread.rotationDeg >= 1e8 || support.spread.positionOverDepth >= 1e8)
    std::snprintf(spreadText, sizeof spreadText, ", pose not determined by its inliers");
  else
    std::snprintf(spreadText, sizeof spreadText, ", pose sigma %.2f deg, %.2f%% of the depth",
                  support.spread.rotationDeg, 100.0 * support.spread.positionOverDepth);
  const std::string supportText =
      std::to_string(n) + " inliers (" + std::to_string(firstInliers) + " of " +
      std::to_string(matches) + " matches before guided matching), " +
      std::to_string(support.covered) + " grid cells" + spreadText + zoomText;
  if (!firstStage || !support.enough) {
    out.message = "not enough support (" + supportText + ")";
    out.stop = firstInliers < params.minInliers || n < params.minInliers ? RecoveryStage::PnpInliers
               : !firstStage ? RecoveryStage::InlierShare
                             : RecoveryStage::InlierSpread;
    return out;
  }
  RelocalisationCandidate c;
  c.worldToCamera = poseFrom(rvec, tvec);
  const auto bestRef = std::max_element(perReference.begin(), perReference.end());
  c.reference = references[static_cast<std::size_t>(bestRef - perReference.begin())].view;
  c.inliers = n;
  c.matches = static_cast<int>(object.size());
  c.reprojectionRmsPx = std::sqrt(sum2 / n);
  c.distinctivePoints = std::move(distinctivePoints);
  c.distinctivePixels = std::move(distinctivePixels);
  out.candidate = c;
  out.message =
      "relocalised on reference " + std::to_string(c.reference) + " (" + supportText + ")";
  return out;
}

}  // namespace reftrack
