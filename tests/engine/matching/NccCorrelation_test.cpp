#include "engine/matching/NccCorrelation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"
#include "engine/features/SyntheticImages.hpp"

using namespace reftrack;

TEST(NccCorrelation, PatchScoresEqualEquation17) {
  const cv::Mat a = test::texturedImage({200, 150}, 1);
  const cv::Mat b = test::texturedImage({200, 150}, 2);
  const std::vector<cv::Point2f> pa = {{30, 40}, {100, 70}, {150, 120}};
  const std::vector<cv::Point2f> pb = {{33, 41}, {60, 20}, {140, 100}};
  const auto A = NccPatches::square(a, pa, 5), B = NccPatches::square(b, pb, 5);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(A.score(i, B, j), nccAt(a, pa[i], b, pb[j], 5), 1e-5);  // float rounding
  EXPECT_NEAR(A.score(0, A, 0), 1.0, 1e-5);
}

TEST(NccCorrelation, InvariantToGainAndOffset) {
  const cv::Mat a = test::texturedImage({120, 120}, 3);
  cv::Mat b;
  a.convertTo(b, CV_8U, 0.5, 40);  // no clipping: 0.5*255+40 < 255
  const std::vector<cv::Point2f> p = {{60, 60}};
  const auto A = NccPatches::square(a, p, 7), B = NccPatches::square(b, p, 7);
  // Rounding b to integers perturbs it by <= 0.5 grey levels: the score stays above 0.999.
  EXPECT_GT(A.score(0, B, 0), 0.999);
}

TEST(NccCorrelation, WarpedWindowsFollowARotation) {
  const cv::Mat a = test::texturedImage({200, 200}, 4);
  const cv::Point2f c(100, 100);
  const double angle = 30.0;
  const cv::Mat R = cv::getRotationMatrix2D(c, angle, 1.0);
  cv::Mat b;
  cv::warpAffine(a, b, R, a.size(), cv::INTER_LINEAR);
  // b(x) = a(R^-1 x): around the centre, window pixel m of b maps to a at c + R^-1 m.
  const double t = angle * CV_PI / 180;
  const cv::Matx22f Rinv(static_cast<float>(std::cos(t)), static_cast<float>(-std::sin(t)),
                         static_cast<float>(std::sin(t)), static_cast<float>(std::cos(t)));
  const auto square = NccPatches::square(b, {c}, 6);
  const auto warped = NccPatches::warped(a, {c}, {Rinv}, 6);
  const auto unwarped = NccPatches::square(a, {c}, 6);
  EXPECT_GT(warped.score(0, square, 0), 0.97);  // two bilinear resamplings blur slightly
  EXPECT_LT(unwarped.score(0, square, 0), warped.score(0, square, 0) - 0.1);
  // The identity map reproduces the square window exactly.
  const auto identity = NccPatches::warped(a, {c}, {cv::Matx22f::eye()}, 6);
  EXPECT_NEAR(identity.score(0, unwarped, 0), 1.0, 1e-5);
}

TEST(NccCorrelation, BorderAndFlatWindowsAreInvalid) {
  const cv::Mat a = test::texturedImage({50, 50}, 5);
  const auto P = NccPatches::square(a, {{2, 2}, {25, 25}, {49, 25}}, 5);
  EXPECT_FALSE(P.valid(0));
  EXPECT_TRUE(P.valid(1));
  EXPECT_FALSE(P.valid(2));
  EXPECT_EQ(P.score(0, P, 1), -1.0f);
  const cv::Mat flat(50, 50, CV_8UC1, cv::Scalar(9));
  EXPECT_FALSE(NccPatches::square(flat, {{25, 25}}, 5).valid(0));
  EXPECT_THROW(NccPatches::square(cv::Mat(), {{1, 1}}, 5), Error);
  EXPECT_THROW(NccPatches::warped(a, {{1, 1}}, {}, 5), Error);
  EXPECT_THROW(NccPatches(0), Error);
  EXPECT_THROW(P.score(1, NccPatches::square(a, {{25, 25}}, 3), 0), Error);
}

TEST(NccCorrelation, WarpedWindowsAreTheBilinearSamplesOfTheMappedPixels) {
  // Against a plain per-pixel implementation (bilinear at c + A (u, v), the window rejected when
  // any pixel leaves [0, cols - 1) x [0, rows - 1)), normalised alike: the same validity and the
  // same values, for windows well inside and windows grazing the image border.
  const cv::Mat a = test::texturedImage({160, 120}, 9);
  const int h = 5;
  const cv::Matx22f A(1.3f, 0.4f, -0.35f, 0.9f);
  std::vector<cv::Point2f> centres;
  for (float y = 3.5f; y < 120; y += 9.25f)
    for (float x = 2.25f; x < 160; x += 7.75f) centres.emplace_back(x, y);
  const NccPatches patches =
      NccPatches::warped(a, centres, std::vector<cv::Matx22f>(centres.size(), A), h);
  int valid = 0, invalid = 0;
  for (size_t i = 0; i < centres.size(); ++i) {
    std::vector<float> expected;
    bool inside = true;
    for (int v = -h; v <= h && inside; ++v)
      for (int u = -h; u <= h; ++u) {
        const float x = centres[i].x + A(0, 0) * u + A(0, 1) * v;
        const float y = centres[i].y + A(1, 0) * u + A(1, 1) * v;
        if (!(x >= 0 && y >= 0 && x < a.cols - 1 && y < a.rows - 1)) {
          inside = false;
          break;
        }
        const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
        const float fx = x - x0, fy = y - y0;
        const uchar* r0 = a.ptr<uchar>(y0) + x0;
        const uchar* r1 = a.ptr<uchar>(y0 + 1) + x0;
        expected.push_back((1 - fy) * ((1 - fx) * r0[0] + fx * r0[1]) +
                           fy * ((1 - fx) * r1[0] + fx * r1[1]));
      }
    ASSERT_EQ(patches.valid(static_cast<int>(i)), inside) << i;
    if (!inside) {
      ++invalid;
      continue;
    }
    ++valid;
    // Normalised as NccPatches does (zero mean, unit norm): compare through the correlation of
    // the reference samples with the window, 1 to float rounding.
    double mean = 0;
    for (float e : expected) mean += e;
    mean /= static_cast<double>(expected.size());
    double ss = 0, dot = 0;
    const float* got = patches.patch(static_cast<int>(i));
    for (size_t k = 0; k < expected.size(); ++k) {
      ss += (expected[k] - mean) * (expected[k] - mean);
      dot += (expected[k] - mean) * got[k];
    }
    EXPECT_NEAR(dot / std::sqrt(ss), 1.0, 1e-5) << i;
  }
  EXPECT_GT(valid, 100);
  EXPECT_GT(invalid, 20);
}
