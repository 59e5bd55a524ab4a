// MetricScale: a length that is not a finite positive number of metres, a point outside the image
// and two points too close together are refused with what is wrong.
#include "engine/mapping/MetricScale.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "ErrorMessage.hpp"

using namespace reftrack;

namespace {
const cv::Size kImage(640, 480);
}

TEST(MetricScale, AFinitePositiveLengthIsAccepted) {
  MetricScale::baseline(0.05).check(kImage);
  MetricScale::distance(0.297, {100, 300}, {500, 310}).check(kImage);
  EXPECT_EQ(MetricScale::baseline(0.05).toString(), "baseline 0.0500 m");
  EXPECT_EQ(MetricScale::distance(0.297, {100, 300}, {500, 310.5}).toString(),
            "distance 0.2970 m between (100.0, 300.0) and (500.0, 310.5) of the first reference");
}

TEST(MetricScale, BadLengthsAreRefused) {
  for (const double bad : {0.0, -0.1, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()}) {
    EXPECT_NE(test::errorMessage([&] {
                MetricScale::baseline(bad).check(kImage);
              }).find("the baseline must be a finite length in metres greater than 0"),
              std::string::npos)
        << bad;
    EXPECT_NE(test::errorMessage([&] {
                MetricScale::distance(bad, {100, 100}, {300, 100}).check(kImage);
              }).find("the distance must be a finite length"),
              std::string::npos)
        << bad;
  }
}

TEST(MetricScale, PointsOutsideTheImageOrTooCloseAreRefused) {
  EXPECT_NE(test::errorMessage([] {
              MetricScale::distance(0.2, {-1, 100}, {300, 100}).check(kImage);
            }).find("(-1.0, 100.0) lies outside the 640x480 reference image"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([] {
              MetricScale::distance(0.2, {100, 100}, {100, 480}).check(kImage);
            }).find("lies outside"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([] {
              MetricScale::distance(0.2, {100, 100},
                                    {std::numeric_limits<double>::quiet_NaN(), 100})
                  .check(kImage);
            }).find("lies outside"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([] {
              MetricScale::distance(0.2, {100, 100}, {105, 104}).check(kImage);
            }).find("px apart (at least 10 needed)"),
            std::string::npos);
}
