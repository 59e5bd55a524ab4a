#include "app/mapview/MapPicture.hpp"

#include <gtest/gtest.h>

#include "TwoViewTestMap.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

namespace {

// 40 points, flat grey images: every coloured pixel is drawn by the picture.
ReferenceMap smallMap() { return test::twoViewTestMap(40, 2, false); }

bool isGrey(const cv::Vec3b& c) { return c[0] == c[1] && c[1] == c[2]; }

}  // namespace

TEST(MapPicture, ShowsMatchesInBothImagesAndPointsIn3d) {
  const ReferenceMap map = smallMap();
  const cv::Mat picture = app::drawMapPicture(map);
  ASSERT_EQ(picture.size(), cv::Size(640, 480));
  ASSERT_EQ(picture.type(), CV_8UC3);
  // Matched corners are drawn in a depth colour (turbo: never grey) in A and in B.
  int colouredA = 0, colouredB = 0;
  for (const ReferenceMatch& m : map.matches) {
    const cv::Point2f a = map.cornersA[static_cast<size_t>(m.cornerA)].pixel;
    const cv::Point2f b = map.cornersB[static_cast<size_t>(m.cornerB)].pixel;
    colouredA += !isGrey(picture.at<cv::Vec3b>(cvRound(a.y), cvRound(a.x)));
    colouredB += !isGrey(picture.at<cv::Vec3b>(cvRound(b.y), cvRound(b.x) + 320));
  }
  EXPECT_EQ(colouredA, 40);
  EXPECT_EQ(colouredB, 40);
  // The 3D panel (bottom half, below its caption) holds coloured points and frusta.
  const cv::Mat bottom = picture(cv::Rect(0, 300, 640, 180));
  int coloured = 0;
  for (int y = 0; y < bottom.rows; ++y)
    for (int x = 0; x < bottom.cols; ++x) coloured += !isGrey(bottom.at<cv::Vec3b>(y, x));
  EXPECT_GT(coloured, 200);
}

TEST(MapPicture, RefusesAnInconsistentMap) {
  ReferenceMap map = smallMap();
  map.matches[3].cornerB = 99;
  EXPECT_THROW(app::drawMapPicture(map), Error);
}

TEST(MapPicture, DrawsEveryReferenceOfAMultiReferenceMap) {
  // Three references of the small map's scene: A, B and C 5 cm above A; 40 points seen by all.
  const ReferenceMap two = smallMap();
  MultiReferenceMap map = MultiReferenceMap::fromPair(two);
  ReferenceView c = map.views[0];
  c.name = "reference_c.png";
  c.T = RigidPose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.05, 0.0));
  c.corners.clear();
  for (std::size_t i = 0; i < map.points.size(); ++i) {
    const Eigen::Vector2d p = map.camera.project(c.T, map.points[i].world);
    c.corners.push_back({cv::Point2f(static_cast<float>(p.x()), static_cast<float>(p.y())), 20});
    map.points[i].observations.push_back({2, static_cast<int>(i)});
  }
  map.views.push_back(c);
  const cv::Mat picture = app::drawMapPicture(map);
  // Two tiles per row at full size: rows 0..1 hold references 0, 1 | 2; the 3D panel below.
  ASSERT_EQ(picture.size(), cv::Size(640, 720));
  int colouredC = 0;
  for (const PointObservation& o : std::vector<PointObservation>{{2, 0}, {2, 7}, {2, 21}}) {
    const cv::Point2f p = map.views[2].corners[static_cast<std::size_t>(o.corner)].pixel;
    colouredC += !isGrey(picture.at<cv::Vec3b>(cvRound(p.y) + 240, cvRound(p.x)));
  }
  EXPECT_EQ(colouredC, 3);
  // Each reference's frustum in its own colour (green, orange, blue) in the 3D panel.
  const cv::Mat bottom = picture(cv::Rect(0, 480 + 60, 640, 180));
  for (const cv::Vec3b& colour :
       {cv::Vec3b(80, 220, 80), cv::Vec3b(80, 160, 255), cv::Vec3b(255, 140, 80)}) {
    int n = 0;
    for (int y = 0; y < bottom.rows; ++y)
      for (int x = 0; x < bottom.cols; ++x)
        n += cv::norm(bottom.at<cv::Vec3b>(y, x), colour, cv::NORM_INF) <= 12 ? 1 : 0;
    EXPECT_GT(n, 20) << colour;
  }
}
