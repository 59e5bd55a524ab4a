#include <gtest/gtest.h>

#include <opencv2/aruco.hpp>
#include <opencv2/imgcodecs.hpp>

#include "app/commands/CommandTestSupport.hpp"

using namespace reftrack;

TEST(MarkerCommand, WritesADetectableMarkerWithTheRequestedIdAndSize) {
  const auto dir = test::freshTempDir("MarkerCommand_Write");
  const auto r = test::runReftrack("marker --out " + (dir / "m.png").string() +
                                       " --dictionary DICT_4X4_50 --id 7 --pixels 200 --margin 40",
                                   dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const cv::Mat img = cv::imread((dir / "m.png").string(), cv::IMREAD_GRAYSCALE);
  ASSERT_EQ(img.size(), cv::Size(280, 280));
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(img, cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50), corners,
                           ids);
  ASSERT_EQ(ids.size(), 1u);
  EXPECT_EQ(ids[0], 7);
  // The outer corner of the black border sits at the margin: (40, 40) within a pixel.
  EXPECT_NEAR(corners[0][0].x, 40.0, 1.0);
  EXPECT_NEAR(corners[0][0].y, 40.0, 1.0);

  const auto def = test::runReftrack("marker --out " + (dir / "d.png").string(), dir);
  ASSERT_EQ(def.exitCode, 0) << def.err;
  cv::aruco::detectMarkers(cv::imread((dir / "d.png").string()),
                           cv::aruco::getPredefinedDictionary(cv::aruco::DICT_6X6_250), corners,
                           ids);
  ASSERT_EQ(ids.size(), 1u);
  EXPECT_EQ(ids[0], 23);
}

TEST(MarkerCommand, BadIdOrDictionaryFailsWithoutWriting) {
  const auto dir = test::freshTempDir("MarkerCommand_Bad");
  const auto r = test::runReftrack(
      "marker --out " + (dir / "m.png").string() + " --dictionary DICT_4X4_50 --id 50", dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("not in DICT_4X4_50"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "m.png"));
  EXPECT_EQ(test::runReftrack("marker --out x.png --pixels 2", dir).exitCode, 2);
}
