#include "render/PixelCanvas.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "render/RenderTarget.hpp"
#include "render/RenderTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::render;

using PixelCanvasTest = test::HeadlessGlTest;

namespace {

cv::Mat drawOnBlack(PixelCanvas& canvas, cv::Size size) {
  RenderTarget target(size);
  target.bind();
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  canvas.draw(size);
  return target.readColourBgr();
}

}  // namespace

// A 4 px wide horizontal line on row 20 covers rows 18..21: fragment centres y + 0.5 inside
// [18, 22) in pixel edges, i.e. exactly the rows whose centres lie within +-2 of y = 20 (18 to
// 21, as the top-left rule keeps 18 and drops 22).
TEST_F(PixelCanvasTest, ThickLineCoversExpectedRows) {
  PixelCanvas canvas;
  canvas.addThickLine({10, 19.5f}, {50, 19.5f}, 4, rgbaFromBgr({0, 0, 255}));
  const cv::Mat image = drawOnBlack(canvas, {64, 40});
  cv::Mat red;
  cv::inRange(image, cv::Scalar(0, 0, 255), cv::Scalar(0, 0, 255), red);
  const cv::Rect box = cv::boundingRect(red);
  EXPECT_EQ(box, cv::Rect(8, 18, 44, 4));  // square caps: 2 px past each end
}

TEST_F(PixelCanvasTest, DiscCentroidOnItsCentre) {
  PixelCanvas canvas;
  const Eigen::Vector2d centre(20.3, 15.8);
  canvas.addDisc(centre.cast<float>(), 6, rgbaFromBgr({255, 255, 255}));
  const cv::Mat image = drawOnBlack(canvas, {48, 32});
  // Binary coverage of a symmetric disc sampled at pixel centres: well under half a pixel.
  EXPECT_LT((test::intensityCentroid(image, centre, 10) - centre).norm(), 0.25);
}

TEST_F(PixelCanvasTest, AlphaBlendsOverWhatIsThere) {
  PixelCanvas canvas;
  canvas.addQuad({-1, -1}, {20, -1}, {20, 20}, {-1, 20}, rgbaFromBgr({0, 0, 255}, 0.5));
  const cv::Mat image = drawOnBlack(canvas, {16, 16});
  // 255 * 0.5 over black: 127 or 128 depending on the rounding of the blend unit.
  EXPECT_NEAR(image.at<cv::Vec3b>(8, 8)[2], 127.5, 1.0);
  EXPECT_EQ(image.at<cv::Vec3b>(8, 8)[0], 0);
}

TEST_F(PixelCanvasTest, RejectsNonFiniteAndNonPositive) {
  PixelCanvas canvas;
  EXPECT_THROW(canvas.addTriangle({0, 0}, {NAN, 1}, {1, 1}, rgbaFromBgr({0, 0, 0})), Error);
  EXPECT_THROW(canvas.addThickLine({0, 0}, {1, 1}, 0, rgbaFromBgr({0, 0, 0})), Error);
  EXPECT_THROW(canvas.addDisc({0, 0}, -1, rgbaFromBgr({0, 0, 0})), Error);
  EXPECT_TRUE(canvas.empty());
  EXPECT_THROW(canvas.draw({0, 5}), Error);
}
