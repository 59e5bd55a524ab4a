#include "engine/geometry/FrameUndistorter.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"

using namespace reftrack;

namespace {

PinholeCamera wideWebcam() {
  const PinholeCamera ideal = PinholeCamera::fromFieldOfView({640, 480}, 50.0);
  return PinholeCamera(ideal.K(), ideal.imageSize(), {-0.3, 0.0, 0.0, 0.0});
}

// A Gaussian dot (sigma 1.5 px) centred at `centre` on black.
cv::Mat dotAt(cv::Size size, cv::Point2d centre) {
  cv::Mat image(size, CV_32F);
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x)
      image.at<float>(y, x) = static_cast<float>(
          200.0 * std::exp(-((x - centre.x) * (x - centre.x) + (y - centre.y) * (y - centre.y)) /
                           (2 * 1.5 * 1.5)));
  return image;
}

cv::Point2d centroid(const cv::Mat& image, cv::Point2d around) {
  double sum = 0, sx = 0, sy = 0;
  for (int y = static_cast<int>(around.y) - 8; y <= static_cast<int>(around.y) + 8; ++y)
    for (int x = static_cast<int>(around.x) - 8; x <= static_cast<int>(around.x) + 8; ++x) {
      if (x < 0 || y < 0 || x >= image.cols || y >= image.rows) continue;
      const double w = image.at<float>(y, x);
      sum += w;
      sx += w * x;
      sy += w * y;
    }
  return {sx / sum, sy / sum};
}

}  // namespace

// A dot recorded through the lens at p ends up at undistortPixels(p) in the undistorted frame.
// Budget: the remap's 1/32 px interpolation grid, and the lens's local scale change across the
// dot (sigma 1.5 px; the centroid's second-order bias is below 0.01 px): 0.05 px.
TEST(FrameUndistorter, DotsMoveToTheirUndistortedPositions) {
  const PinholeCamera camera = wideWebcam();
  const FrameUndistorter undistorter(camera);
  double worst = 0.0;
  for (const cv::Point2f& p : {cv::Point2f(320, 240), cv::Point2f(100.3f, 80.6f),
                               cv::Point2f(560.2f, 420.7f), cv::Point2f(600.5f, 60.25f)}) {
    const cv::Mat undistorted = undistorter.undistort(dotAt(camera.imageSize(), p));
    const cv::Point2f expected = camera.undistortPixels({p})[0];
    const cv::Point2d got = centroid(undistorted, expected);
    worst = std::max(worst, std::hypot(got.x - expected.x, got.y - expected.y));
  }
  EXPECT_LT(worst, 0.05);
}

TEST(FrameUndistorter, PassesPinholeFramesThroughAndChecksTheSize) {
  const FrameUndistorter pinhole(PinholeCamera::fromFieldOfView({640, 480}, 50.0));
  const cv::Mat frame(480, 640, CV_8UC1, cv::Scalar(9));
  EXPECT_EQ(pinhole.undistort(frame).data, frame.data);
  const FrameUndistorter lens(wideWebcam());
  EXPECT_THROW(lens.undistort(cv::Mat(240, 320, CV_8UC1)), Error);
  EXPECT_EQ(lens.undistort(frame).size(), frame.size());
}
