#include "engine/relocalisation/KeypointFeatures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"
#include "engine/tracking/TrackingTestImages.hpp"

namespace reftrack {
namespace {

// The hand-written Hamming matcher against OpenCV's brute force on the same descriptors: the
// same nearest neighbour and ratio-test decisions (ties aside: random 256-bit rows have none
// that matter at ratio 0.8 in this seed), for 32-byte (ORB) and 61-byte (AKAZE) rows.
TEST(MatchDescriptors, HammingAgreesWithOpenCvBruteForce) {
  for (const int bytes : {32, 61}) {
    cv::Mat train(300, bytes, CV_8U), query(200, bytes, CV_8U);
    cv::RNG rng(3);
    rng.fill(train, cv::RNG::UNIFORM, 0, 256);
    rng.fill(query, cv::RNG::UNIFORM, 0, 256);
    // Half the queries are noisy copies of train rows (a few bits flipped): clear matches.
    for (int q = 0; q < 100; ++q) {
      train.row(q * 3).copyTo(query.row(q));
      query.at<std::uint8_t>(q, q % bytes) ^= 0x5;
    }
    const std::vector<cv::DMatch> ours =
        matchDescriptors(query, train, cv::NORM_HAMMING, 0.8, false);
    std::vector<std::vector<cv::DMatch>> knn;
    cv::BFMatcher(cv::NORM_HAMMING).knnMatch(query, train, knn, 2);
    std::vector<cv::DMatch> theirs;
    for (const auto& m : knn)
      if (m.size() == 2 && m[0].distance < 0.8 * m[1].distance) theirs.push_back(m[0]);
    ASSERT_EQ(ours.size(), theirs.size()) << bytes;
    for (std::size_t i = 0; i < ours.size(); ++i) {
      EXPECT_EQ(ours[i].queryIdx, theirs[i].queryIdx);
      EXPECT_EQ(ours[i].trainIdx, theirs[i].trainIdx);
      EXPECT_FLOAT_EQ(ours[i].distance, theirs[i].distance);
    }
    EXPECT_GE(static_cast<int>(ours.size()), 100);  // every planted copy passes
    // Mutual: a planted pair survives both ways; the result is a subset.
    const std::vector<cv::DMatch> mutual =
        matchDescriptors(query, train, cv::NORM_HAMMING, 0.8, true);
    EXPECT_GE(static_cast<int>(mutual.size()), 100);
    EXPECT_LE(mutual.size(), ours.size());
  }
}

// Ties and every remainder of the eight-row blocks: ORB-length rows of few distinct bit patterns
// (distances tie often), train row counts 1-17 and 300; matchDescriptors must pick the earliest
// train row at the smallest distance and apply the ratio test to the two smallest distances
// (brute force with descriptorDistance), for every query.
TEST(MatchDescriptors, EarliestNearestRowAndTwoSmallestDistancesWithTies) {
  cv::RNG rng(11);
  for (const int rows : {1, 2, 7, 8, 9, 15, 16, 17, 300}) {
    cv::Mat train(rows, 32, CV_8U), query(60, 32, CV_8U);
    for (cv::Mat* m : {&train, &query})
      for (int r = 0; r < m->rows; ++r)
        for (int c = 0; c < 32; ++c) m->at<std::uint8_t>(r, c) = rng.uniform(0, 4) == 0 ? 0x1 : 0;
    for (const double ratio : {0.8, 1.01}) {
      const std::vector<cv::DMatch> ours =
          matchDescriptors(query, train, cv::NORM_HAMMING, ratio, false);
      std::vector<cv::DMatch> expected;
      for (int q = 0; q < query.rows && rows >= 2; ++q) {
        float first = 1e9f, second = 1e9f;
        int best = -1;
        for (int t = 0; t < rows; ++t) {
          const float d = descriptorDistance(query, q, train, t, cv::NORM_HAMMING);
          if (d < first) {
            second = first;
            first = d;
            best = t;
          } else if (d < second) {
            second = d;
          }
        }
        if (first < ratio * second) expected.emplace_back(q, best, first);
      }
      ASSERT_EQ(ours.size(), expected.size()) << rows << " rows, ratio " << ratio;
      for (std::size_t i = 0; i < ours.size(); ++i) {
        EXPECT_EQ(ours[i].queryIdx, expected[i].queryIdx) << rows;
        EXPECT_EQ(ours[i].trainIdx, expected[i].trainIdx) << rows;
        EXPECT_FLOAT_EQ(ours[i].distance, expected[i].distance) << rows;
      }
    }
  }
}

// descriptorDistance is cv::norm's distance, exactly, for ORB and AKAZE rows (Hamming) and SIFT
// rows (L2, float): random rows, every pair of the first 20 x 20.
TEST(DescriptorDistance, EqualsOpenCvNorm) {
  cv::RNG rng(5);
  for (const int bytes : {32, 61}) {
    cv::Mat a(20, bytes, CV_8U), b(20, bytes, CV_8U);
    rng.fill(a, cv::RNG::UNIFORM, 0, 256);
    rng.fill(b, cv::RNG::UNIFORM, 0, 256);
    for (int i = 0; i < a.rows; ++i)
      for (int j = 0; j < b.rows; ++j)
        ASSERT_EQ(descriptorDistance(a, i, b, j, cv::NORM_HAMMING),
                  static_cast<float>(cv::norm(a.row(i), b.row(j), cv::NORM_HAMMING)))
            << bytes << " bytes, rows " << i << ", " << j;
  }
  cv::Mat a(20, 128, CV_32F), b(20, 128, CV_32F);
  rng.fill(a, cv::RNG::UNIFORM, 0.0, 255.0);
  rng.fill(b, cv::RNG::UNIFORM, 0.0, 255.0);
  for (int i = 0; i < a.rows; ++i)
    EXPECT_FLOAT_EQ(descriptorDistance(a, i, b, 19 - i, cv::NORM_L2),
                    static_cast<float>(cv::norm(a.row(i), b.row(19 - i), cv::NORM_L2)));
}

// descriptorDistances is cv::batchDistance's matrix, exactly (ORB, AKAZE and SIFT rows).
TEST(DescriptorDistances, EqualBatchDistance) {
  cv::RNG rng(6);
  for (const int bytes : {32, 61}) {
    cv::Mat a(37, bytes, CV_8U), b(53, bytes, CV_8U);
    rng.fill(a, cv::RNG::UNIFORM, 0, 256);
    rng.fill(b, cv::RNG::UNIFORM, 0, 256);
    cv::Mat expected;
    cv::batchDistance(a, b, expected, CV_32S, cv::noArray(), cv::NORM_HAMMING);
    expected.convertTo(expected, CV_32F);
    const cv::Mat ours = descriptorDistances(a, b, cv::NORM_HAMMING);
    ASSERT_EQ(ours.type(), CV_32F);
    ASSERT_EQ(ours.size(), expected.size());
    EXPECT_EQ(cv::norm(ours, expected, cv::NORM_INF), 0.0) << bytes << " bytes";
  }
  cv::Mat a(20, 128, CV_32F), b(30, 128, CV_32F), expected;
  rng.fill(a, cv::RNG::UNIFORM, 0.0, 255.0);
  rng.fill(b, cv::RNG::UNIFORM, 0.0, 255.0);
  cv::batchDistance(a, b, expected, CV_32F, cv::noArray(), cv::NORM_L2);
  EXPECT_EQ(cv::norm(descriptorDistances(a, b, cv::NORM_L2), expected, cv::NORM_INF), 0.0);
  EXPECT_THROW(descriptorDistances(a, cv::Mat(5, 61, CV_8U, cv::Scalar(0)), cv::NORM_HAMMING),
               Error);
}

TEST(MatchDescriptors, RefusesDescriptorsOfDifferentLengths) {
  const cv::Mat a(10, 32, CV_8U, cv::Scalar(1)), b(10, 61, CV_8U, cv::Scalar(1));
  EXPECT_THROW(matchDescriptors(a, b, cv::NORM_HAMMING, 0.8, false), Error);
  EXPECT_TRUE(matchDescriptors(a, cv::Mat(), cv::NORM_HAMMING, 0.8, false).empty());
}

TEST(KeypointFeatures, EachKindFindsAtMostTheCapAndNothingOnABlackImage) {
  const cv::Mat textured = test::texturedImage({640, 480}, 5);
  for (const std::string kind : {"orb", "akaze", "sift"}) {
    const KeypointFeatures f(kind);
    std::vector<cv::KeyPoint> k;
    cv::Mat d;
    f.detectAndDescribe(textured, 500, k, d);
    EXPECT_EQ(static_cast<int>(k.size()), 500) << kind << ": the texture has far more keypoints";
    EXPECT_EQ(d.rows, 500) << kind;
    EXPECT_EQ(d.type(), kind == "sift" ? CV_32F : CV_8U) << kind;
    f.detectAndDescribe(cv::Mat::zeros(480, 640, CV_8UC3), 500, k, d);
    EXPECT_TRUE(k.empty()) << kind;
    EXPECT_TRUE(d.empty()) << kind;
  }
  EXPECT_THROW(KeypointFeatures("surf"), Error);
}

// ORB's finer levels are the image magnified (1.2x per level): their keypoints are smaller than
// the image's own finest (patch 31 px: 31 / 1.2^3 at the finest), still in image pixels, and a
// good share of the cap goes to them (ORB gives each level 1.2x the next one's share).
TEST(KeypointFeatures, OrbFinerLevelsGiveSmallerKeypointsInImagePixels) {
  const cv::Mat textured = test::texturedImage({320, 240}, 7);
  const KeypointFeatures orb("orb");
  std::vector<cv::KeyPoint> plain, finer;
  cv::Mat d;
  orb.detectAndDescribe(textured, 2000, plain, d);
  orb.detectAndDescribe(textured, 2000, finer, d, 3, 0);
  ASSERT_FALSE(finer.empty());
  EXPECT_EQ(d.rows, static_cast<int>(finer.size()));
  float smallestPlain = 1e9f, smallestFiner = 1e9f;
  for (const cv::KeyPoint& k : plain) smallestPlain = std::min(smallestPlain, k.size);
  int belowImageScale = 0;
  for (const cv::KeyPoint& k : finer) {
    smallestFiner = std::min(smallestFiner, k.size);
    belowImageScale += k.size < 30.0f;
    EXPECT_TRUE(k.pt.inside(cv::Rect2f(0, 0, 320, 240))) << k.pt;
  }
  EXPECT_NEAR(smallestPlain, 31.0f, 1e-3f);
  EXPECT_NEAR(smallestFiner, 31.0f / std::pow(1.2f, 3.0f), 0.05f);
  EXPECT_GT(belowImageScale, static_cast<int>(finer.size()) / 4);
}

// Detection on a reduced copy (relocalisation.sift_frame_scale) gives keypoints in the image's own
// pixels: an image made 2x larger and detected at scale 0.5 finds the original's SIFT keypoints at
// twice their positions (within 0.6 px of the large image: the reduction is exact up to
// interpolation, and SIFT localises to a fraction of a pixel) and twice their size.
TEST(KeypointFeatures, AReducedDetectionReportsKeypointsInTheImagesPixels) {
  const cv::Mat small = test::texturedImage({320, 240}, 11);
  cv::Mat large;
  cv::resize(small, large, cv::Size(), 2.0, 2.0, cv::INTER_CUBIC);
  const KeypointFeatures sift("sift");
  std::vector<cv::KeyPoint> direct, reduced;
  cv::Mat d1, d2;
  sift.detectAndDescribe(small, 300, direct, d1);
  sift.detectAndDescribe(large, 300, reduced, d2, 0, 0, 0.5);
  ASSERT_GE(direct.size(), 200u);
  ASSERT_GE(reduced.size(), 200u);
  int close = 0;
  for (const cv::KeyPoint& k : direct) {
    const cv::Point2f expected = (k.pt + cv::Point2f(0.5f, 0.5f)) * 2.0f - cv::Point2f(0.5f, 0.5f);
    for (const cv::KeyPoint& r : reduced)
      if (cv::norm(r.pt - expected) < 0.6 && std::abs(r.size - 2.0f * k.size) < 0.2f * k.size) {
        ++close;
        break;
      }
  }
  EXPECT_GT(close, static_cast<int>(direct.size()) * 3 / 4);
  std::vector<cv::KeyPoint> k;
  cv::Mat d;
  EXPECT_THROW(sift.detectAndDescribe(small, 10, k, d, 0, 0, 0.0), Error);
  EXPECT_THROW(sift.detectAndDescribe(small, 10, k, d, 0, 0, 1.5), Error);
}

}  // namespace
}  // namespace reftrack
