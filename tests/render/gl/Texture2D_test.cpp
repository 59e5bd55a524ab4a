#include "render/gl/Texture2D.hpp"

#include <glad/gl.h>
#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "render/RenderTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::render;

using Texture2DTest = test::HeadlessGlTest;

namespace {

// Reads level 0 of the bound texture back as RGB bytes (GL_RGB, top row = image row 0).
cv::Mat readTextureRgb(const Texture2D& texture) {
  texture.bind(0);
  cv::Mat rgb(texture.size(), CV_8UC3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGB, GL_UNSIGNED_BYTE, rgb.data);
  return rgb;
}

}  // namespace

TEST_F(Texture2DTest, UploadsBgrAndGreyExactlyAndUpdatesInPlace) {
  cv::Mat bgr(5, 7, CV_8UC3);
  cv::randu(bgr, 0, 256);
  Texture2D texture;
  texture.upload(bgr, false);
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  EXPECT_EQ(cv::norm(readTextureRgb(texture), rgb, cv::NORM_INF), 0);
  const unsigned int id = texture.id();
  // A non-continuous view (a column range) of the same size re-uses the storage.
  cv::Mat wide(5, 10, CV_8UC3);
  cv::randu(wide, 0, 256);
  const cv::Mat view = wide.colRange(2, 9);
  texture.upload(view, false);
  cv::cvtColor(view, rgb, cv::COLOR_BGR2RGB);
  EXPECT_EQ(cv::norm(readTextureRgb(texture), rgb, cv::NORM_INF), 0);
  EXPECT_EQ(texture.id(), id);
}

TEST_F(Texture2DTest, GreyTextureIsUploadedAsItsValues) {
  cv::Mat grey(3, 5, CV_8UC1);
  cv::randu(grey, 0, 256);
  Texture2D texture;
  texture.upload(grey, true);
  texture.bind(0);
  cv::Mat red(3, 5, CV_8UC1);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_UNSIGNED_BYTE, red.data);
  EXPECT_EQ(cv::norm(red, grey, cv::NORM_INF), 0);
  EXPECT_EQ(texture.size(), cv::Size(5, 3));
}

TEST_F(Texture2DTest, RejectsEmptyAndUnsupportedImages) {
  Texture2D texture;
  EXPECT_THROW(texture.upload(cv::Mat(), false), Error);
  EXPECT_THROW(texture.upload(cv::Mat(4, 4, CV_32FC1, cv::Scalar(0)), false), Error);
  EXPECT_THROW(texture.upload(cv::Mat(4, 4, CV_8UC4, cv::Scalar(0)), false), Error);
}
