#include "engine/config/HomographyTrackerParams.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(HomographyTrackerParams, RoundTrip) {
  HomographyTrackerParams in;
  in.guidedSearchHalfSizePx = 4.5;
  in.frameToFramePrediction = false;
  in.reacquireWholeImage = false;
  HomographyTrackerParams out;
  roundTrip(in, out);
  EXPECT_DOUBLE_EQ(out.guidedSearchHalfSizePx, 4.5);
  EXPECT_FALSE(out.frameToFramePrediction);
  EXPECT_FALSE(out.reacquireWholeImage);
}

TEST(HomographyTrackerParams, BadFieldIsNamed) {
  HomographyTrackerParams p;
  p.guidedSearchHalfSizePx = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.guided_search_half_size_px"),
            std::string::npos);
  auto fs = parseYaml("h: { frame_to_frame_prediction: 3 }\n");
  HomographyTrackerParams q;
  EXPECT_NE(errorMessage([&] { q.read(fs["h"]); }).find("homography.frame_to_frame_prediction"),
            std::string::npos);
}
