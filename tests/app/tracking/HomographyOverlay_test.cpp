#include "app/tracking/HomographyOverlay.hpp"

#include <gtest/gtest.h>

#include "render/context/GlContext.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(HomographyOverlay, DrawsLabelsAtTheirMappedPositionsOnlyWhenRegistered) {
  const auto context = render::createHeadlessContext();
  const cv::Size size(320, 240);
  const cv::Mat frame(size, CV_8UC3, cv::Scalar(60, 60, 60));
  const PinholeCamera camera = PinholeCamera::fromFieldOfView(size, 60);
  const AnnotationSet labels({{"A", {100, 100}}});
  TrackingResult result;
  result.status = "tracking";
  OverlaySettings settings;
  settings.showLabels = false;
  HomographyOverlay overlay;
  const cv::Matx33d shift(1, 0, 40, 0, 1, 20, 0, 0, 1);  // the label lands at (140, 120)
  const cv::Mat drawn = overlay.composite(frame, camera, result, settings, "", shift, labels);
  ASSERT_EQ(drawn.size(), size);
  // The label's dot (radius 3 px) covers its mapped position; the unmapped one stays grey.
  const cv::Vec3b at = drawn.at<cv::Vec3b>(120, 140);
  EXPECT_GT(at[1], 200);  // yellow: strong green and red
  EXPECT_GT(at[2], 200);
  EXPECT_EQ(drawn.at<cv::Vec3b>(100, 100), cv::Vec3b(60, 60, 60));
  // Not registered: neither outline nor label, the frame comes back unchanged.
  const cv::Mat plain =
      overlay.composite(frame, camera, result, settings, "", std::nullopt, labels);
  EXPECT_EQ(cv::norm(plain, frame, cv::NORM_INF), 0.0);
}

// A reference of another size than the frame (another camera): the outline follows the
// reference's own border (160x120, shifted by (40, 30)), not the frame's.
TEST(HomographyOverlay, OutlinesAReferenceOfAnotherSizeByItsOwnBorder) {
  const auto context = render::createHeadlessContext();
  const cv::Size size(320, 240);
  const cv::Mat frame(size, CV_8UC3, cv::Scalar(60, 60, 60));
  const PinholeCamera camera = PinholeCamera::fromFieldOfView(size, 60);
  TrackingResult result;
  result.status = "tracking";
  OverlaySettings settings;
  settings.showLabels = false;
  HomographyOverlay overlay;
  const cv::Matx33d shift(1, 0, 40, 0, 1, 30, 0, 0, 1);
  const cv::Mat drawn = overlay.composite(frame, camera, result, settings, "", shift,
                                          AnnotationSet{}, cv::Size(160, 120));
  // The outline (255, 200, 0), 1 px wide, drawn at or next to a pixel: its blue channel.
  const auto outlined = [&](int x, int y) {
    int blue = 0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        blue = std::max<int>(blue, drawn.at<cv::Vec3b>(y + dy, x + dx)[0]);
    return blue > 120;  // the grey frame is 60
  };
  EXPECT_TRUE(outlined(120, 30));    // the top side, mid-way
  EXPECT_TRUE(outlined(200, 90));    // the right side (x = 199.5)
  EXPECT_FALSE(outlined(260, 30));   // beyond the reference's width
  EXPECT_FALSE(outlined(120, 200));  // below its height
}
