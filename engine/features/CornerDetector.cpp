#include "engine/features/CornerDetector.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/RmsContrast.hpp"
#include "engine/features/SubPixelCorner.hpp"

namespace reftrack {

namespace {

struct Candidate {
  cv::Point2f position;  // at full resolution
  float response;
};

// Harris measure det(M) - k tr(M)^2 of the structure tensor summed over a block around (x, y),
// from central differences. Computed only at FAST candidates: on a 640x480 frame this costs
// ~0.1 ms against ~2.2 ms for cv::cornerHarris over the whole image (measured, one core).
float harrisFromSums(int sxx, int syy, int sxy, double k) {
  // The sums are of doubled central differences (exact integers), scaled once here.
  const double xx = 0.25 * sxx, yy = 0.25 * syy, xy = 0.25 * sxy, tr = xx + yy;
  return static_cast<float>(xx * yy - xy * xy - k * tr * tr);
}

float harrisAt(const cv::Mat& img, int x, int y, int half, double k) {
  // Integer sums of the doubled central differences (exact: |2 g| <= 255, a 7x7 block of squares
  // stays below 2^22); 3x faster than summing doubles per pixel.
  int sxx = 0, syy = 0, sxy = 0;
  for (int v = y - half; v <= y + half; ++v) {
    const uchar* up = img.ptr<uchar>(v - 1);
    const uchar* row = img.ptr<uchar>(v);
    const uchar* down = img.ptr<uchar>(v + 1);
    for (int u = x - half; u <= x + half; ++u) {
      const int gx = row[u + 1] - row[u - 1];
      const int gy = down[u] - up[u];
      sxx += gx * gx;
      syy += gy * gy;
      sxy += gx * gy;
    }
  }
  return harrisFromSums(sxx, syy, sxy, k);
}

#if CV_SIMD128
// The same sums, eight pixels of a block row at a time with OpenCV's universal intrinsics
// (SSE2/NEON): 16-bit differences, exact 32-bit dot products, lanes past the block masked to
// zero, so the result is bit-identical to harrisAt. The scalar loop was most of a 640x480
// tracked frame's corner detection (~3500 FAST candidates scored per frame on the real postcard
// clip); measured with callgrind on that clip: 2.7 -> 1.2 M instructions per frame in detect()
// itself, the same corners.
// Reads up to 8 pixels right of the block: the caller checks x + half + 8 < cols.
float harrisAtSimd(const cv::Mat& img, int x, int y, int half, double k) {
  alignas(16) static const short kLaneMasks[9][8] = {
      {0, 0, 0, 0, 0, 0, 0, 0},        {-1, 0, 0, 0, 0, 0, 0, 0},
      {-1, -1, 0, 0, 0, 0, 0, 0},      {-1, -1, -1, 0, 0, 0, 0, 0},
      {-1, -1, -1, -1, 0, 0, 0, 0},    {-1, -1, -1, -1, -1, 0, 0, 0},
      {-1, -1, -1, -1, -1, -1, 0, 0},  {-1, -1, -1, -1, -1, -1, -1, 0},
      {-1, -1, -1, -1, -1, -1, -1, -1}};
  cv::v_int32x4 sxx = cv::v_setzero_s32(), syy = cv::v_setzero_s32(), sxy = cv::v_setzero_s32();
  for (int v = y - half; v <= y + half; ++v) {
    const uchar* up = img.ptr<uchar>(v - 1);
    const uchar* row = img.ptr<uchar>(v);
    const uchar* down = img.ptr<uchar>(v + 1);
    for (int u = x - half; u <= x + half; u += 8) {
      const cv::v_int16x8 mask = cv::v_load(kLaneMasks[std::min(8, x + half + 1 - u)]);
      const cv::v_int16x8 gx = (cv::v_reinterpret_as_s16(cv::v_load_expand(row + u + 1)) -
                                cv::v_reinterpret_as_s16(cv::v_load_expand(row + u - 1))) &
                               mask;
      const cv::v_int16x8 gy = (cv::v_reinterpret_as_s16(cv::v_load_expand(down + u)) -
                                cv::v_reinterpret_as_s16(cv::v_load_expand(up + u))) &
                               mask;
      sxx += cv::v_dotprod(gx, gx);
      syy += cv::v_dotprod(gy, gy);
      sxy += cv::v_dotprod(gx, gy);
    }
  }
  return harrisFromSums(cv::v_reduce_sum(sxx), cv::v_reduce_sum(syy), cv::v_reduce_sum(sxy), k);
}
#endif

int pyramidLevelFor(cv::Size size, bool detectAtPaperScale) {
  if (!detectAtPaperScale) return 0;
  // Halve while the halved image still holds at least 90% of the paper's 320x240 pixels.
  int level = 0;
  double area = static_cast<double>(size.width) * size.height;
  while (area / 4.0 >= 0.9 * kPaperImageWidth * kPaperImageHeight) {
    area /= 4.0;
    ++level;
  }
  return level;
}

// FAST candidates with their Harris responses (0 where a candidate cannot be scored).
struct ScoredCandidates {
  std::vector<cv::KeyPoint> points;
  std::vector<float> responses;
};

// cv::FAST over two row bands at once, each band's candidates scored (`harris(x, y)`) in the same
// task (OpenCV's threads; one thread: in turn). Each band has the 3 rows of the other that FAST's
// circle reads, so the candidates are those of the whole image in the same row order (checked
// keypoint for keypoint on 145 frames of the desk, ViSP and Kinect clips at thresholds 5-40).
template <typename Harris>
void fastInBands(const cv::Mat& image, int threshold, const Harris& harris, ScoredCandidates& out) {
  constexpr int kBands = 2, kCircle = 3;
  thread_local ScoredCandidates callersBands[kBands];
  ScoredCandidates* bands = callersBands;  // the workers fill the caller's vectors
  cv::parallel_for_(
      cv::Range(0, kBands),
      [&](const cv::Range& range) {
        for (int b = range.start; b < range.end; ++b) {
          const int first = std::max(0, image.rows * b / kBands - kCircle);
          const int last = std::min(image.rows, image.rows * (b + 1) / kBands + kCircle);
          cv::FAST(image.rowRange(first, last), bands[b].points, threshold, false);
          bands[b].responses.clear();
          for (cv::KeyPoint& k : bands[b].points) {
            k.pt.y += static_cast<float>(first);
            bands[b].responses.push_back(
                harris(static_cast<int>(k.pt.x), static_cast<int>(k.pt.y)));
          }
        }
      },
      kBands);
  out.points.clear();
  out.responses.clear();
  for (int b = 0; b < kBands; ++b) {
    out.points.insert(out.points.end(), bands[b].points.begin(), bands[b].points.end());
    out.responses.insert(out.responses.end(), bands[b].responses.begin(), bands[b].responses.end());
  }
}

}  // namespace

cv::Mat toGray8(const cv::Mat& image) {
  if (image.empty()) throw Error("image is empty");
  cv::Mat src = image;
  if (image.depth() == CV_16U) image.convertTo(src, CV_8U, 1.0 / 256.0);
  if (src.depth() != CV_8U)
    throw Error("unsupported image type (expected 8-bit grey or BGR), got depth " +
                std::to_string(image.depth()));
  if (src.channels() == 1) return src;
  cv::Mat gray;
  if (src.channels() == 3)
    cv::cvtColor(src, gray, cv::COLOR_BGR2GRAY);
  else if (src.channels() == 4)
    cv::cvtColor(src, gray, cv::COLOR_BGRA2GRAY);
  else
    throw Error("unsupported image with " + std::to_string(src.channels()) + " channels");
  return gray;
}

CornerDetector::CornerDetector(CornerParams params) : params_(params) { params_.check(); }

std::vector<Corner> CornerDetector::detect(const cv::Mat& image) const {
  return detect(ImagePyramid(toGray8(image)));
}

std::vector<Corner> CornerDetector::detect(const ImagePyramid& pyramid) const {
  const cv::Mat& gray = pyramid.image();
  const cv::Size size = gray.size();
  const int count = params_.countFor(size);
  const int level = pyramidLevelFor(size, params_.detectAtPaperScale);
  // On a pyramid level, the candidates FAST is tuned to are for the corners this detector has
  // been delivering (three times a decaying maximum of the last calls' counts, so one blurred
  // frame does not lower it), not for params.count when the quality and spacing rules keep far
  // fewer: the homography tracker's 1280x720 frames ask for 762 corners and keep ~150-200, and
  // the candidates for 762 cost ~30% of the detection (paper-scale detection of the 6-DOF webcam
  // sequences: 1280x720 1.16 -> 0.85 ms, 1920x1080 1.19 -> 0.99 ms, 93-95% of the corners the
  // same; the homography errors unchanged). Full-resolution detection keeps the whole budget:
  // there the corners are the 6-DOF tracker's measurements, and the adapted budget cost accuracy
  // (1920x1080 webcam sequence: cube error 0.504 -> 0.528 px mean).
  const int wanted =
      level > 0 && producedHint_ > 0 ? std::min(count, std::max(16, 3 * producedHint_)) : count;
  const cv::Mat& work = pyramid.level(level);
  const float toFull = static_cast<float>(1 << level);
  // cv::pyrDown filters around the even pixels: level pixel u sits at full-resolution 2^level u.

  const int half = params_.blockSize / 2;
  const int border = std::max(half + 2, 3);
  // Reused between calls: FAST without suppression returns thousands of keypoints on textured
  // frames, and a fresh vector each time costs more in page faults than FAST itself.
  thread_local ScoredCandidates keypoints, fewer;
  // A candidate's Harris response; 0 when its block leaves the working level.
  const auto harrisOf = [&](int x, int y) {
    if (x < border || y < border || x >= work.cols - border || y >= work.rows - border) return 0.0f;
#if CV_SIMD128
    return x + half + 8 < work.cols ? harrisAtSimd(work, x, y, half, params_.harrisK)
                                    : harrisAt(work, x, y, half, params_.harrisK);
#else
    return harrisAt(work, x, y, half, params_.harrisK);
#endif
  };
  // No FAST non-maximum suppression: its strict test drops pixel-aligned corners whose
  // neighbours tie; the Harris ranking with minimum spacing below does the suppression. The
  // threshold is halved while there are fewer than kMinCandidatesPerCorner candidates per corner
  // wanted, and raised while there are more than kMaxCandidatesPerCorner (scoring thousands of
  // candidates on a richly textured frame costs more than the FAST passes), keeping the minimum.
  // The next call starts from the threshold this one settled on (consecutive frames are alike).
  // FAST fires on several neighbouring pixels of one corner, so the minimum is 4 raw candidates
  // per corner (with 2, a frame darkened by 30% after bright ones kept the brighter frames'
  // threshold and yielded 39-48 of 110 corners).
  constexpr int kMaxCandidatesPerCorner = 12, kMinCandidatesPerCorner = 4;
  int threshold = thresholdHint_ > 0 ? thresholdHint_ : params_.fastThreshold;
  fastInBands(work, threshold, harrisOf, keypoints);
  while (static_cast<int>(keypoints.points.size()) < kMinCandidatesPerCorner * wanted &&
         threshold > 4) {
    threshold /= 2;
    fastInBands(work, threshold, harrisOf, keypoints);
  }
  while (static_cast<int>(keypoints.points.size()) > kMaxCandidatesPerCorner * wanted &&
         threshold < 120) {
    threshold = threshold * 3 / 2;
    fastInBands(work, threshold, harrisOf, fewer);
    if (static_cast<int>(fewer.points.size()) < kMinCandidatesPerCorner * wanted) break;
    std::swap(keypoints, fewer);
  }
  thresholdHint_ = threshold;

  // Only the strongest candidate of each cell of side minDist / sqrt(2) (on the working level)
  // can be chosen first there (two points in one cell are closer than minDist), so the others
  // are dropped before sorting: FAST fires on several neighbouring pixels of each corner.
  const double minDist = params_.minDistanceFor(size);
  const double bucket = std::max(1.0, minDist / toFull / std::sqrt(2.0));
  const int bucketCols = static_cast<int>(work.cols / bucket) + 1;
  const int bucketRows = static_cast<int>(work.rows / bucket) + 1;
  thread_local std::vector<int> bestInBucket;
  bestInBucket.assign(static_cast<size_t>(bucketCols * bucketRows), -1);
  std::vector<Candidate> candidates;
  candidates.reserve(std::min<size_t>(keypoints.points.size(), bestInBucket.size()));
  float best = 0.0f;
  for (std::size_t i = 0; i < keypoints.points.size(); ++i) {
    const int x = static_cast<int>(keypoints.points[i].pt.x);
    const int y = static_cast<int>(keypoints.points[i].pt.y);
    const float r = keypoints.responses[i];
    if (r <= 0.0f) continue;
    best = std::max(best, r);
    int& slot = bestInBucket[static_cast<size_t>(static_cast<int>(y / bucket) * bucketCols +
                                                 static_cast<int>(x / bucket))];
    if (slot < 0) {
      slot = static_cast<int>(candidates.size());
      candidates.push_back({cv::Point2f(x * toFull, y * toFull), r});
    } else if (r > candidates[static_cast<size_t>(slot)].response) {
      candidates[static_cast<size_t>(slot)] = {cv::Point2f(x * toFull, y * toFull), r};
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.response > b.response; });
  const float minResponse = static_cast<float>(params_.quality) * best;

  // Spread: a per-cell quota on the coarse grid in the first pass, then the strongest of the
  // rest; both passes keep the minimum spacing (checked on a fine occupancy grid).
  const double cellSize = std::max(1.0, minDist);
  const int occCols = static_cast<int>(size.width / cellSize) + 1;
  const int occRows = static_cast<int>(size.height / cellSize) + 1;
  std::vector<std::vector<cv::Point2f>> occupancy(static_cast<size_t>(occCols * occRows));
  const auto farEnough = [&](cv::Point2f p) {
    const int cx = static_cast<int>(p.x / cellSize), cy = static_cast<int>(p.y / cellSize);
    for (int y = std::max(0, cy - 1); y <= std::min(occRows - 1, cy + 1); ++y)
      for (int x = std::max(0, cx - 1); x <= std::min(occCols - 1, cx + 1); ++x)
        for (const cv::Point2f& q : occupancy[static_cast<size_t>(y * occCols + x)]) {
          const cv::Point2f d = p - q;
          if (d.dot(d) < minDist * minDist) return false;
        }
    return true;
  };
  const int cells = params_.gridColumns * params_.gridRows;
  const int quota = (count + cells - 1) / cells;
  std::vector<int> perCell(static_cast<size_t>(cells), 0);
  std::vector<char> taken(candidates.size(), 0);
  std::vector<cv::Point2f> chosen;
  std::vector<float> chosenResponse;
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t i = 0; i < candidates.size() && static_cast<int>(chosen.size()) < count; ++i) {
      const Candidate& c = candidates[i];
      if (taken[i] || c.response < minResponse) continue;
      const int gx = std::min(params_.gridColumns - 1,
                              static_cast<int>(c.position.x * params_.gridColumns / size.width));
      const int gy = std::min(params_.gridRows - 1,
                              static_cast<int>(c.position.y * params_.gridRows / size.height));
      int& inCell = perCell[static_cast<size_t>(gy * params_.gridColumns + gx)];
      if (pass == 0 && inCell >= quota) continue;
      if (!farEnough(c.position)) continue;
      taken[i] = 1;
      ++inCell;
      chosen.push_back(c.position);
      chosenResponse.push_back(c.response);
      occupancy[static_cast<size_t>(static_cast<int>(c.position.y / cellSize) * occCols +
                                    static_cast<int>(c.position.x / cellSize))]
          .push_back(c.position);
    }
  }
  if (chosen.empty()) return {};

  const int win = params_.subPixelHalfWindow;
  if (level > 0) {
    // Candidates from a pyramid level are up to 2^level px off: refine them on that level first
    // (cheap), so that the full-resolution pass starts within a pixel and keeps the base window.
    for (cv::Point2f& c : chosen) c *= 1.0f / toFull;
    refineCornersSubPixel(work, chosen, win);
    for (cv::Point2f& c : chosen) c *= toFull;
  }
  // Refinement can move a weak corner off the image; such points are dropped.
  const auto inImage = [&](cv::Point2f p) {
    return p.x >= 0 && p.y >= 0 && p.x <= size.width - 1 && p.y <= size.height - 1;
  };
  // Each corner refined and its contrast measured on its own, in two shares at once (OpenCV's
  // threads; the same corners on any number of threads).
  std::vector<float> contrast(chosen.size(), 0.0f);
  cv::parallel_for_(
      cv::Range(0, static_cast<int>(chosen.size())),
      [&](const cv::Range& range) {
        std::vector<cv::Point2f> share(chosen.begin() + range.start, chosen.begin() + range.end);
        refineCornersSubPixel(gray, share, win);
        for (int i = range.start; i < range.end; ++i) {
          const cv::Point2f p = share[static_cast<std::size_t>(i - range.start)];
          chosen[static_cast<std::size_t>(i)] = p;
          if (inImage(p))
            contrast[static_cast<std::size_t>(i)] =
                static_cast<float>(rmsContrast(gray, p, params_.contrastWindow));
        }
      },
      chosen.size() >= 64 ? 2 : 1);
  std::vector<Corner> corners;
  corners.reserve(chosen.size());
  for (size_t i = 0; i < chosen.size(); ++i)
    if (inImage(chosen[i])) corners.push_back({chosen[i], chosenResponse[i], contrast[i]});
  producedHint_ = std::max(static_cast<int>(corners.size()), producedHint_ * 7 / 8);
  return corners;
}

}  // namespace reftrack
