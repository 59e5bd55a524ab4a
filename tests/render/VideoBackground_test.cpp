#include "render/VideoBackground.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "render/RenderTarget.hpp"
#include "render/RenderTestSupport.hpp"
#include "render/Viewport.hpp"

using namespace reftrack;
using namespace reftrack::render;

using VideoBackgroundTest = test::HeadlessGlTest;

// Same size as the viewport: the read-back must equal the input bit for bit (tolerance 0).
TEST_F(VideoBackgroundTest, PixelExactAtImageSize) {
  const cv::Size size(321, 239);  // odd sizes catch row-alignment mistakes
  RenderTarget target(size);
  target.bind();
  VideoBackground background;
  cv::Mat bgr(size, CV_8UC3);
  cv::randu(bgr, 0, 256);
  background.draw(bgr);
  EXPECT_EQ(cv::norm(target.readColourBgr(), bgr, cv::NORM_INF), 0);
  // A second frame of the same size (in-place texture update) and a grey frame.
  cv::randu(bgr, 0, 256);
  background.draw(bgr);
  EXPECT_EQ(cv::norm(target.readColourBgr(), bgr, cv::NORM_INF), 0);
  cv::Mat grey(size, CV_8UC1);
  cv::randu(grey, 0, 256);
  background.draw(grey);
  cv::Mat greyBgr;
  cv::cvtColor(grey, greyBgr, cv::COLOR_GRAY2BGR);
  EXPECT_EQ(cv::norm(target.readColourBgr(), greyBgr, cv::NORM_INF), 0);
}

TEST_F(VideoBackgroundTest, LetterboxedImageFillsItsViewportOnly) {
  RenderTarget target({200, 100});
  target.bind();
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  const cv::Mat image(50, 50, CV_8UC3, cv::Scalar(10, 200, 30));
  const Viewport viewport = fitImage(image.size(), target.size());
  EXPECT_EQ(viewport, (Viewport{50, 0, 100, 100}));
  applyViewport(viewport);
  VideoBackground background;
  background.draw(image);
  const cv::Mat out = target.readColourBgr();
  EXPECT_EQ(out.at<cv::Vec3b>(50, 100), cv::Vec3b(10, 200, 30));
  EXPECT_EQ(out.at<cv::Vec3b>(50, 20), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(out.at<cv::Vec3b>(50, 180), cv::Vec3b(0, 0, 0));
}

TEST_F(VideoBackgroundTest, ScaledImageKeepsTopRowAtTop) {
  RenderTarget target({64, 64});
  target.bind();
  cv::Mat image(32, 32, CV_8UC3, cv::Scalar(0, 0, 0));
  image.rowRange(0, 8).setTo(cv::Scalar(255, 255, 255));
  VideoBackground background;
  background.draw(image);
  const cv::Mat out = target.readColourBgr();
  EXPECT_EQ(out.at<cv::Vec3b>(2, 30), cv::Vec3b(255, 255, 255));
  EXPECT_EQ(out.at<cv::Vec3b>(60, 30), cv::Vec3b(0, 0, 0));
}

TEST_F(VideoBackgroundTest, RejectsBadImages) {
  VideoBackground background;
  EXPECT_THROW(background.draw(cv::Mat()), Error);
  EXPECT_THROW(background.draw(cv::Mat(4, 4, CV_16UC1, cv::Scalar(0))), Error);
}
