#include "render/RenderTarget.hpp"

#include <glad/gl.h>
#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "render/RenderTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::render;

using RenderTargetTest = test::HeadlessGlTest;

TEST_F(RenderTargetTest, ReadsColourTopRowFirstAsBgr) {
  RenderTarget target({7, 5});
  target.bind();
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  // Paint the top GL row (window y = 4), which must come back as image row 0.
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 4, 7, 1);
  glClearColor(1.0f, 0.0f, 0.0f, 1.0f);  // red
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  const cv::Mat image = target.readColourBgr();
  ASSERT_EQ(image.type(), CV_8UC3);
  ASSERT_EQ(image.size(), cv::Size(7, 5));
  EXPECT_EQ(image.at<cv::Vec3b>(0, 3), cv::Vec3b(0, 0, 255));
  EXPECT_EQ(image.at<cv::Vec3b>(4, 3), cv::Vec3b(0, 0, 0));
}

TEST_F(RenderTargetTest, ClearedDepthReadsZero) {
  RenderTarget target({4, 3});
  target.bind();
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  const cv::Mat depth = target.readDepthMetres(0.1, 10.0);
  ASSERT_EQ(depth.type(), CV_32F);
  EXPECT_EQ(cv::countNonZero(depth), 0);
  // Depth value 0.5 with n = 0.1, f = 10 is Z = f n / (f - 0.5 (f - n)) = 1/5.05 m.
  glClearDepth(0.5);
  glClear(GL_DEPTH_BUFFER_BIT);
  EXPECT_NEAR(target.readDepthMetres(0.1, 10.0).at<float>(1, 1), 1.0 / 5.05, 1e-5);
  EXPECT_THROW(target.readDepthMetres(1.0, 0.5), Error);
}

TEST_F(RenderTargetTest, RejectsImpossibleSizes) {
  EXPECT_THROW(RenderTarget({0, 10}), Error);
  EXPECT_THROW(RenderTarget({1 << 20, 10}), Error);
}
