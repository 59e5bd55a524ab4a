#include "app/plot/PlotCanvas.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

TEST(PlotCanvas, DrawsSeriesWhereTheDataSaysAndSavesPng) {
  const auto dir = test::freshTempDir("PlotCanvas_Draw");
  app::PlotCanvas plot("test", "x", "y", {640, 480});
  plot.addLine("line", {0, 1, 2, 3}, {0, 1, 2, 3}, cv::Scalar(255, 0, 0));
  plot.addScatter("points", {0.5, 2.5}, {2.5, 0.5}, cv::Scalar(0, 0, 255));
  plot.save(dir / "p.png");
  const cv::Mat img = cv::imread((dir / "p.png").string());
  ASSERT_EQ(img.size(), cv::Size(640, 480));
  auto colourNear = [&](cv::Point2d p, cv::Vec3b want) {
    // Within 2 px of the mapped point (anti-aliased, 2 px wide lines).
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const cv::Vec3b c = img.at<cv::Vec3b>(cvRound(p.y) + dy, cvRound(p.x) + dx);
        if (cv::norm(cv::Vec3i(c) - cv::Vec3i(want)) < 60) return true;
      }
    return false;
  };
  EXPECT_TRUE(colourNear(plot.toPixel(1.5, 1.5), {255, 0, 0}));  // on the line
  EXPECT_TRUE(colourNear(plot.toPixel(0.5, 2.5), {0, 0, 255}));  // a scatter point
  EXPECT_TRUE(colourNear(plot.toPixel(2.5, 0.5), {0, 0, 255}));
  EXPECT_FALSE(colourNear(plot.toPixel(2.5, 2.0), {255, 0, 0}));  // away from both
  // Data increase to the right and upwards.
  EXPECT_LT(plot.toPixel(0, 0).x, plot.toPixel(3, 0).x);
  EXPECT_GT(plot.toPixel(0, 0).y, plot.toPixel(0, 3).y);
}

TEST(PlotCanvas, EqualAspectAndBadInput) {
  app::PlotCanvas plot("top", "x", "y", {800, 400});
  plot.setEqualAspect(true);
  plot.addLine("a", {0, 1}, {0, 1}, cv::Scalar(0, 0, 0));
  const cv::Point2d o = plot.toPixel(0, 0), a = plot.toPixel(1, 0), b = plot.toPixel(0, 1);
  EXPECT_NEAR(a.x - o.x, o.y - b.y, 1e-9);  // one unit is as long on both axes
  EXPECT_THROW(plot.addLine("bad", {0, 1}, {0}, cv::Scalar()), Error);
  EXPECT_THROW(app::PlotCanvas("tiny", "", "", {10, 10}), Error);
  const auto dir = test::freshTempDir("PlotCanvas_Bad");
  EXPECT_THROW(plot.save(dir / "missing" / "p.png"), Error);
  EXPECT_THROW(plot.save(dir / "p.unknownext"), Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "p.unknownext"));
}
