#include "engine/matching/NccCorrelation.hpp"

#include <gtest/gtest.h>

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
