#include "engine/relocalisation/KeypointFeatures.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "engine/core/Error.hpp"

namespace reftrack {

KeypointFeatures::KeypointFeatures(const std::string& kind) : kind_(kind) {
  if (kind != "orb" && kind != "akaze" && kind != "sift")
    throw Error("unknown keypoint kind '" + kind + "' (orb, akaze or sift)");
}

int KeypointFeatures::normType() const { return kind_ == "sift" ? cv::NORM_L2 : cv::NORM_HAMMING; }

void KeypointFeatures::detectAndDescribe(const cv::Mat& image, int maxKeypoints,
                                         std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors,
                                         int finerLevels, int coarserLevels, double scale) const {
  if (!(scale > 0.0 && scale <= 1.0))
    throw Error("keypoint detection scale " + std::to_string(scale) + " is not in (0, 1]");
  cv::Mat gray = image;
  if (image.channels() == 3) cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  if (scale < 1.0) cv::resize(gray, gray, cv::Size(), scale, scale, cv::INTER_AREA);
  keypoints.clear();
  descriptors.release();
  if (kind_ == "orb") {
    // FAST threshold 20 (OpenCV's default); 8 levels of 1.2: keypoints from 1x to 3.6x scale,
    // with the finer levels (firstLevel: the image upsampled) and coarser ones around them.
    cv::ORB::create(maxKeypoints, 1.2f, 8 + finerLevels + coarserLevels, 31, finerLevels)
        ->detectAndCompute(gray, cv::noArray(), keypoints, descriptors);
  } else if (kind_ == "sift") {
    cv::SIFT::create(maxKeypoints)->detectAndCompute(gray, cv::noArray(), keypoints, descriptors);
  } else {
    // AKAZE has no cap of its own: detect all, keep the strongest, then describe those only.
    const cv::Ptr<cv::AKAZE> akaze = cv::AKAZE::create();
    akaze->detect(gray, keypoints);
    cv::KeyPointsFilter::retainBest(keypoints, maxKeypoints);
    if (!keypoints.empty()) akaze->compute(gray, keypoints, descriptors);
  }
  // SIFT may return a few more than asked (equal responses); the layer's size is the cap.
  if (static_cast<int>(keypoints.size()) > maxKeypoints) {
    keypoints.resize(static_cast<std::size_t>(maxKeypoints));
    descriptors = descriptors.rowRange(0, maxKeypoints).clone();
  }
  if (keypoints.empty()) descriptors = cv::Mat();
  // Back to the image's pixels: cv::resize maps pixel centres (x_small = (x + 0.5) s - 0.5).
  if (scale < 1.0)
    for (cv::KeyPoint& k : keypoints) {
      k.pt = (k.pt + cv::Point2f(0.5f, 0.5f)) / static_cast<float>(scale) - cv::Point2f(0.5f, 0.5f);
      k.size /= static_cast<float>(scale);
    }
}

namespace {

struct NearestTwo {
  int best = -1;
  float first = 0.0f, second = 0.0f;
};

// Hamming distances, hand-written: cv::BFMatcher's Hamming kNN on this Debian OpenCV 4.6 build
// takes 24 ms for 1000 x 900 ORB descriptors (no hardware popcount in its baseline), this loop
// 1.2 ms with the CPU's popcount instruction (selected at run time where the CPU has one).
// Distance of two rows of `bytes` bytes; Words > 0: exactly 8 * Words bytes (unrolled).
// The popcount instruction is chosen at run time where the CPU has one (x86): the loops below
// are inlined into a copy compiled for it (REFTRACK_POPCNT_TARGET) and a default copy, and
// cpuHasPopcnt() picks one. Not GCC's target_clones: that makes an IFUNC whose resolver runs
// while the program is relocated, before a sanitizer's runtime is initialised, and under
// ThreadSanitizer the instrumented resolver crashed every executable linking this file.
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define REFTRACK_POPCNT_TARGET __attribute__((target("popcnt")))
#define REFTRACK_ALWAYS_INLINE inline __attribute__((always_inline))
bool cpuHasPopcnt() {
  static const bool has = __builtin_cpu_supports("popcnt");
  return has;
}
#else
#define REFTRACK_POPCNT_TARGET
#define REFTRACK_ALWAYS_INLINE inline
bool cpuHasPopcnt() { return false; }
#endif

template <int Words>
REFTRACK_ALWAYS_INLINE int hamming(const std::uint8_t* a, const std::uint8_t* b, int bytes) {
  int d = 0;
  const int words = Words > 0 ? Words : bytes / 8;
  for (int w = 0; w < words; ++w) {
    std::uint64_t x, y;
    std::memcpy(&x, a + 8 * w, 8);
    std::memcpy(&y, b + 8 * w, 8);
    d += __builtin_popcountll(x ^ y);
  }
  if (Words == 0)
    for (int i = 8 * words; i < bytes; ++i)
      d += __builtin_popcount(static_cast<unsigned>(a[i] ^ b[i]));
  return d;
}

// The two smallest distances offered and the index of the smallest.
struct NearestTwoSoFar {
  int first = std::numeric_limits<int>::max(), second = first, best = -1;
  void offer(int d, int t) {
    if (d < first) {
      second = first;
      first = d;
      best = t;
    } else if (d < second) {
      second = d;
    }
  }
  NearestTwo result() const {
    return {best, static_cast<float>(first), static_cast<float>(second)};
  }
};

template <int Words>
REFTRACK_ALWAYS_INLINE void nearestTwoRows(const cv::Mat& query, const cv::Mat& train,
                                           std::vector<NearestTwo>& out) {
  for (int q = 0; q < query.rows; ++q) {
    const std::uint8_t* a = query.ptr<std::uint8_t>(q);
    NearestTwoSoFar n;
    for (int t = 0; t < train.rows; ++t)
      n.offer(hamming<Words>(a, train.ptr<std::uint8_t>(t), query.cols), t);
    out[static_cast<std::size_t>(q)] = n.result();
  }
}

// Hamming distances, hand-written: cv::BFMatcher's Hamming kNN on this Debian OpenCV 4.6 build
// takes 24 ms for 1000 x 900 ORB descriptors (no hardware popcount in its baseline), this loop
// 1.2 ms with the CPU's popcount instruction (selected at run time where the CPU has one).
REFTRACK_ALWAYS_INLINE void nearestTwoHammingRows(const cv::Mat& query, const cv::Mat& train,
                                                  std::vector<NearestTwo>& out) {
  if (query.cols == 32)
    nearestTwoRows<4>(query, train, out);  // ORB
  else
    nearestTwoRows<0>(query, train, out);  // AKAZE: 61 bytes
}
REFTRACK_POPCNT_TARGET void nearestTwoHammingPopcnt(const cv::Mat& query, const cv::Mat& train,
                                                    std::vector<NearestTwo>& out) {
  nearestTwoHammingRows(query, train, out);
}
void nearestTwoHammingScalar(const cv::Mat& query, const cv::Mat& train,
                             std::vector<NearestTwo>& out) {
  if (cpuHasPopcnt())
    nearestTwoHammingPopcnt(query, train, out);
  else
    nearestTwoHammingRows(query, train, out);
}

#if defined(__GNUC__) && defined(__x86_64__)
#define REFTRACK_HAVE_VPOPCNT 1
// ORB rows (32 bytes) with AVX-512 VPOPCNTDQ, where the CPU has it (run-time check): one XOR and
// one vector popcount per pair. Measured on 1500 x 1700 descriptors (a relocalisation attempt's
// matching against one reference): 6.4 -> 2.8 ms, the same nearest two as the scalar loop.
#define REFTRACK_VPOPCNT_TARGET __attribute__((target("avx2,avx512f,avx512vl,avx512vpopcntdq")))
// The Hamming distance of the 32 bytes in `a` to the 32 bytes at `b`.
REFTRACK_VPOPCNT_TARGET inline int orbHammingVpopcnt(__m256i a, const std::uint8_t* b) {
  const __m256i p = _mm256_popcnt_epi64(
      _mm256_xor_si256(a, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b))));
  const __m128i h = _mm_add_epi64(_mm256_castsi256_si128(p), _mm256_extracti128_si256(p, 1));
  return static_cast<int>(_mm_cvtsi128_si64(h) + _mm_extract_epi64(h, 1));
}

// Eight train rows at a time, from a word-planar copy of the train rows (plane w holds the
// w-th 64-bit word of every row), so that one 512-bit popcount gives eight rows' partial
// distances with no horizontal sums; each lane keeps the two smallest distances it saw and the
// first row of its smallest, and the lanes are merged at the end (the earliest row wins a tie,
// as in the scalar loop). Measured on a relocalisation attempt's matching (1500 frame x ~3500
// reference rows, two references): 2.8 -> 0.9 ms per reference.
REFTRACK_VPOPCNT_TARGET void nearestTwoOrbVpopcnt(const cv::Mat& query, const cv::Mat& train,
                                                  std::vector<NearestTwo>& out) {
  const int rows = train.rows, blocked = rows - rows % 8;
  thread_local std::vector<std::uint64_t> planes;
  planes.resize(4 * static_cast<std::size_t>(blocked));
  for (int t = 0; t < blocked; ++t)
    for (int w = 0; w < 4; ++w)
      std::memcpy(&planes[static_cast<std::size_t>(w) * blocked + t], train.ptr(t) + 8 * w, 8);
  const __m512i laneIndex = _mm512_set_epi64(7, 6, 5, 4, 3, 2, 1, 0);
  for (int q = 0; q < query.rows; ++q) {
    const std::uint8_t* a = query.ptr(q);
    std::uint64_t words[4];
    std::memcpy(words, a, 32);
    const __m512i q0 = _mm512_set1_epi64(static_cast<long long>(words[0]));
    const __m512i q1 = _mm512_set1_epi64(static_cast<long long>(words[1]));
    const __m512i q2 = _mm512_set1_epi64(static_cast<long long>(words[2]));
    const __m512i q3 = _mm512_set1_epi64(static_cast<long long>(words[3]));
    __m512i first = _mm512_set1_epi64(std::numeric_limits<int>::max());
    __m512i second = first;
    __m512i best = _mm512_set1_epi64(-1);
    const std::uint64_t* p0 = planes.data();
    const std::uint64_t* p1 = p0 + blocked;
    const std::uint64_t* p2 = p1 + blocked;
    const std::uint64_t* p3 = p2 + blocked;
    for (int t = 0; t < blocked; t += 8) {
      const __m512i d = _mm512_add_epi64(
          _mm512_add_epi64(_mm512_popcnt_epi64(_mm512_xor_si512(q0, _mm512_loadu_si512(p0 + t))),
                           _mm512_popcnt_epi64(_mm512_xor_si512(q1, _mm512_loadu_si512(p1 + t)))),
          _mm512_add_epi64(_mm512_popcnt_epi64(_mm512_xor_si512(q2, _mm512_loadu_si512(p2 + t))),
                           _mm512_popcnt_epi64(_mm512_xor_si512(q3, _mm512_loadu_si512(p3 + t)))));
      const __mmask8 smaller = _mm512_cmplt_epi64_mask(d, first);
      // The masked forms with every lane set: GCC 12's unmasked min/max pass an "undefined"
      // vector that its -Wmaybe-uninitialized reports.
      second =
          _mm512_mask_min_epi64(second, 0xFF, second, _mm512_mask_max_epi64(first, 0xFF, first, d));
      first = _mm512_mask_min_epi64(first, 0xFF, first, d);
      best =
          _mm512_mask_mov_epi64(best, smaller, _mm512_add_epi64(laneIndex, _mm512_set1_epi64(t)));
    }
    alignas(64) long long f[8], s2[8], b[8];
    _mm512_store_si512(f, first);
    _mm512_store_si512(s2, second);
    _mm512_store_si512(b, best);
    NearestTwoSoFar n;
    for (int lane = 0; lane < 8; ++lane) {
      if (b[lane] < 0) continue;
      // A lane's smallest, then its second: the earliest row wins a tie across lanes.
      const int d = static_cast<int>(f[lane]), row = static_cast<int>(b[lane]);
      if (d < n.first || (d == n.first && row < n.best)) {
        n.second = std::min(n.second, n.first);
        n.first = d;
        n.best = row;
      } else {
        n.second = std::min(n.second, d);
      }
      n.second = std::min(n.second, static_cast<int>(s2[lane]));
    }
    for (int t = blocked; t < rows; ++t) {
      const __m256i av = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(a));
      n.offer(orbHammingVpopcnt(av, train.ptr(t)), t);
    }
    out[static_cast<std::size_t>(q)] = n.result();
  }
}

bool cpuHasVpopcnt() {
  static const bool has = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                          __builtin_cpu_supports("avx512vpopcntdq");
  return has;
}
#endif

void nearestTwoHamming(const cv::Mat& query, const cv::Mat& train, std::vector<NearestTwo>& out) {
  out.assign(static_cast<std::size_t>(query.rows), NearestTwo{});
#ifdef REFTRACK_HAVE_VPOPCNT
  if (query.cols == 32 && cpuHasVpopcnt()) {
    nearestTwoOrbVpopcnt(query, train, out);
    return;
  }
#endif
  nearestTwoHammingScalar(query, train, out);
}

REFTRACK_ALWAYS_INLINE int hammingRow(const std::uint8_t* a, const std::uint8_t* b, int bytes) {
  return bytes == 32 ? hamming<4>(a, b, bytes) : hamming<0>(a, b, bytes);
}
REFTRACK_POPCNT_TARGET int hammingRowPopcnt(const std::uint8_t* a, const std::uint8_t* b,
                                            int bytes) {
  return hammingRow(a, b, bytes);
}
int hammingDistance(const std::uint8_t* a, const std::uint8_t* b, int bytes) {
  return cpuHasPopcnt() ? hammingRowPopcnt(a, b, bytes) : hammingRow(a, b, bytes);
}

REFTRACK_ALWAYS_INLINE void hammingMatrixRows(const cv::Mat& query, const cv::Mat& train,
                                              cv::Mat& out) {
  for (int q = 0; q < query.rows; ++q) {
    const std::uint8_t* a = query.ptr<std::uint8_t>(q);
    float* row = out.ptr<float>(q);
    for (int t = 0; t < train.rows; ++t)
      row[t] = static_cast<float>(query.cols == 32
                                      ? hamming<4>(a, train.ptr<std::uint8_t>(t), 32)
                                      : hamming<0>(a, train.ptr<std::uint8_t>(t), query.cols));
  }
}
REFTRACK_POPCNT_TARGET void hammingMatrixPopcnt(const cv::Mat& query, const cv::Mat& train,
                                                cv::Mat& out) {
  hammingMatrixRows(query, train, out);
}
void hammingMatrixScalar(const cv::Mat& query, const cv::Mat& train, cv::Mat& out) {
  if (cpuHasPopcnt())
    hammingMatrixPopcnt(query, train, out);
  else
    hammingMatrixRows(query, train, out);
}

#ifdef REFTRACK_HAVE_VPOPCNT
REFTRACK_VPOPCNT_TARGET void hammingMatrixOrbVpopcnt(const cv::Mat& query, const cv::Mat& train,
                                                     cv::Mat& out) {
  for (int q = 0; q < query.rows; ++q) {
    const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(query.ptr(q)));
    float* row = out.ptr<float>(q);
    for (int t = 0; t < train.rows; ++t)
      row[t] = static_cast<float>(orbHammingVpopcnt(a, train.ptr(t)));
  }
}
#endif

std::vector<NearestTwo> nearestTwo(const cv::Mat& query, const cv::Mat& train, int normType) {
  std::vector<NearestTwo> out;
  if (normType == cv::NORM_HAMMING) {
    nearestTwoHamming(query, train, out);
    return out;
  }
  out.assign(static_cast<std::size_t>(query.rows), NearestTwo{});
  std::vector<std::vector<cv::DMatch>> knn;
  cv::BFMatcher(normType).knnMatch(query, train, knn, 2);
  for (const std::vector<cv::DMatch>& m : knn)
    if (m.size() == 2)
      out[static_cast<std::size_t>(m[0].queryIdx)] = {m[0].trainIdx, m[0].distance, m[1].distance};
  return out;
}

// Best train row per query row passing the ratio test, -1 where none.
std::vector<int> ratioBest(const cv::Mat& query, const cv::Mat& train, int normType, double ratio,
                           std::vector<float>* distances) {
  std::vector<int> best(static_cast<std::size_t>(query.rows), -1);
  if (distances) distances->assign(best.size(), 0.0f);
  if (query.empty() || train.rows < 2) return best;
  if (query.cols != train.cols || query.type() != train.type())
    throw Error("descriptor matching: query and train descriptors differ in type or length");
  const std::vector<NearestTwo> nn = nearestTwo(query, train, normType);
  for (std::size_t q = 0; q < nn.size(); ++q) {
    if (nn[q].best < 0 || nn[q].first >= ratio * nn[q].second) continue;
    best[q] = nn[q].best;
    if (distances) (*distances)[q] = nn[q].first;
  }
  return best;
}
}  // namespace

std::vector<cv::DMatch> matchDescriptors(const cv::Mat& query, const cv::Mat& train, int normType,
                                         double ratio, bool mutual) {
  std::vector<float> distance;
  const std::vector<int> forward = ratioBest(query, train, normType, ratio, &distance);
  std::vector<int> backward;
  if (mutual) backward = ratioBest(train, query, normType, ratio, nullptr);
  std::vector<cv::DMatch> out;
  for (int q = 0; q < query.rows; ++q) {
    const int t = forward[static_cast<std::size_t>(q)];
    if (t < 0) continue;
    if (mutual && backward[static_cast<std::size_t>(t)] != q) continue;
    out.emplace_back(q, t, distance[static_cast<std::size_t>(q)]);
  }
  return out;
}

cv::Mat descriptorDistances(const cv::Mat& query, const cv::Mat& train, int normType) {
  if (query.empty() || train.empty()) return cv::Mat(query.rows, train.rows, CV_32F);
  if (query.cols != train.cols || query.type() != train.type())
    throw Error("descriptor distances: query and train descriptors differ in type or length");
  if (normType != cv::NORM_HAMMING || query.type() != CV_8U) {
    cv::Mat out;
    cv::batchDistance(query, train, out, CV_32F, cv::noArray(), normType);
    return out;
  }
  cv::Mat out(query.rows, train.rows, CV_32F);
#ifdef REFTRACK_HAVE_VPOPCNT
  if (query.cols == 32 && cpuHasVpopcnt()) {
    hammingMatrixOrbVpopcnt(query, train, out);
    return out;
  }
#endif
  hammingMatrixScalar(query, train, out);
  return out;
}

float descriptorDistance(const cv::Mat& a, int rowA, const cv::Mat& b, int rowB, int normType) {
  if (normType == cv::NORM_HAMMING && a.type() == CV_8U && b.type() == CV_8U && a.cols == b.cols)
    return static_cast<float>(
        hammingDistance(a.ptr<std::uint8_t>(rowA), b.ptr<std::uint8_t>(rowB), a.cols));
  return static_cast<float>(cv::norm(a.row(rowA), b.row(rowB), normType));
}

}  // namespace reftrack
