#include "render/Annotations2D.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "render/RenderTarget.hpp"
#include "render/RenderTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::render;

namespace {

const cv::Size kSize(160, 120);

cv::Mat drawOnBlack(Annotations2D& annotations) {
  RenderTarget target(kSize);
  target.bind();
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  annotations.draw(kSize);
  return target.readColourBgr();
}

cv::Mat exactly(const cv::Mat& image, const cv::Scalar& colour) {
  cv::Mat mask;
  cv::inRange(image, colour, colour, mask);
  return mask;
}

}  // namespace

TEST(Annotations2D, ClipsLinesToTheImage) {
  // The diagonal x = y enters at the top-left corner (-0.5, -0.5) and leaves at the bottom.
  const auto diagonal = clipLineToImage(1, -1, 0, kSize);
  ASSERT_TRUE(diagonal);
  const double top = std::min(diagonal->first.y, diagonal->second.y);
  const double bottom = std::max(diagonal->first.y, diagonal->second.y);
  EXPECT_NEAR(top, -0.5, 1e-9);
  EXPECT_NEAR(bottom, kSize.height - 0.5, 1e-9);
  // Vertical x = 100 spans the full height; a line beyond the image misses it.
  const auto vertical = clipLineToImage(1, 0, -100, kSize);
  ASSERT_TRUE(vertical);
  EXPECT_NEAR(std::abs(vertical->first.y - vertical->second.y), kSize.height, 1e-9);
  EXPECT_FALSE(clipLineToImage(1, 0, -500, kSize));
  EXPECT_FALSE(clipLineToImage(0, 0, 1, kSize));
  EXPECT_THROW(clipLineToImage(NAN, 1, 0, kSize), Error);
}

using Annotations2DTest = test::HeadlessGlTest;

// A 1 px segment from (10,20) to (60,20) is the quad [9.5, 60.5] x [19.5, 20.5] in pixel
// coordinates: exactly the centres of row 20, columns 10..60.
TEST_F(Annotations2DTest, SegmentAndDotLandOnTheRightPixels) {
  Annotations2D annotations;
  annotations.addSegment({10, 20}, {60, 20}, 1, cv::Scalar(0, 0, 255));
  const cv::Point2f dot(100.3f, 70.6f);
  annotations.addDot(dot, 5, cv::Scalar(255, 255, 255));
  const cv::Mat image = drawOnBlack(annotations);
  const cv::Mat red = exactly(image, cv::Scalar(0, 0, 255));
  EXPECT_EQ(cv::boundingRect(red), cv::Rect(10, 20, 51, 1));
  EXPECT_EQ(cv::countNonZero(red), 51);
  const cv::Moments m = cv::moments(exactly(image, cv::Scalar(255, 255, 255)), true);
  // Binary coverage of a symmetric disc at pixel centres: under a quarter pixel off.
  EXPECT_NEAR(m.m10 / m.m00, dot.x, 0.25);
  EXPECT_NEAR(m.m01 / m.m00, dot.y, 0.25);
}

TEST_F(Annotations2DTest, InfiniteLineAndPolylineDraw) {
  Annotations2D annotations;
  EXPECT_TRUE(annotations.addInfiniteLine(1, 0, -100, kSize, 1, cv::Scalar(0, 255, 0)));
  EXPECT_FALSE(annotations.addInfiniteLine(1, 0, -500, kSize, 1, cv::Scalar(0, 255, 0)));
  annotations.addPolyline({{20, 60}, {60, 60}, {40, 100}}, true, 3, cv::Scalar(255, 0, 0));
  const cv::Mat image = drawOnBlack(annotations);
  const cv::Mat green = exactly(image, cv::Scalar(0, 255, 0));
  EXPECT_EQ(cv::boundingRect(green), cv::Rect(100, 0, 1, kSize.height));
  const cv::Mat blue = exactly(image, cv::Scalar(255, 0, 0));
  for (const cv::Point p : {cv::Point(20, 60), cv::Point(60, 60), cv::Point(40, 100),
                            cv::Point(30, 80), cv::Point(40, 60)})
    EXPECT_EQ(blue.at<uchar>(p), 255) << p;
  EXPECT_EQ(blue.at<uchar>(80, 40), 0);  // inside the triangle, not on it
}

TEST_F(Annotations2DTest, LabelDrawsInsideItsBox) {
  Annotations2D annotations;
  const cv::Point2f topLeft(20, 30);
  const std::string text = "pose 12.5 mm";
  annotations.addText(topLeft, text, cv::Scalar(255, 255, 255), 2.0f);
  const cv::Mat image = drawOnBlack(annotations);
  const cv::Mat white = exactly(image, cv::Scalar(255, 255, 255));
  const cv::Rect2f box = Annotations2D::textBox(topLeft, text, 2.0f);
  const cv::Rect drawn = cv::boundingRect(white);
  EXPECT_GT(cv::countNonZero(white), 100);
  EXPECT_GE(drawn.x, box.x);
  EXPECT_GE(drawn.y, box.y);
  EXPECT_LE(drawn.x + drawn.width, box.x + box.width);
  EXPECT_LE(drawn.y + drawn.height, box.y + box.height);
  // Over a bright background the dark box shows up behind the text.
  RenderTarget target(kSize);
  target.bind();
  glClearColor(1, 1, 1, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  annotations.draw(kSize);
  const cv::Mat onWhite = target.readColourBgr();
  EXPECT_LT(onWhite.at<cv::Vec3b>(static_cast<int>(box.y + 1), static_cast<int>(box.x + 1))[0],
            128);
  EXPECT_EQ(onWhite.at<cv::Vec3b>(5, 150), cv::Vec3b(255, 255, 255));
}

TEST_F(Annotations2DTest, RejectsNonFiniteAndNonPositive) {
  Annotations2D annotations;
  EXPECT_THROW(annotations.addDot({NAN, 1}, 2, cv::Scalar(0, 0, 0)), Error);
  EXPECT_THROW(annotations.addSegment({0, 0}, {1, 1}, 0, cv::Scalar(0, 0, 0)), Error);
  EXPECT_THROW(annotations.addText({0, 0}, "x", cv::Scalar(0, 0, 0), -1), Error);
  EXPECT_THROW(annotations.addPolyline({{0, 0}, {INFINITY, 1}}, false, 1, cv::Scalar(0, 0, 0)),
               Error);
  EXPECT_TRUE(annotations.empty());
}
