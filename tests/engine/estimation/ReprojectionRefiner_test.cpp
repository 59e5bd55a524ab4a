#include "engine/estimation/ReprojectionRefiner.hpp"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <random>

namespace reftrack {
namespace {

struct Scene {
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  cv::Matx33d K{520.0, 0.0, 320.0, 0.0, 515.0, 240.0, 0.0, 0.0, 1.0};
  cv::Vec3d rTrue{0.10, -0.20, 0.05}, tTrue{0.05, -0.02, 1.10};
};

// 150 points of a bumpy desk about 1 m away, their projections with 0.3 px Gaussian noise.
Scene noisyScene() {
  Scene s;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> xy(-0.4, 0.4), z(-0.05, 0.05);
  std::normal_distribution<double> noise(0.0, 0.3);
  for (int i = 0; i < 150; ++i) s.object.emplace_back(xy(rng), xy(rng), z(rng));
  cv::projectPoints(s.object, s.rTrue, s.tTrue, s.K, cv::noArray(), s.image);
  for (cv::Point2d& p : s.image) p += cv::Point2d(noise(rng), noise(rng));
  return s;
}

// From a start 0.6 degrees and 1 cm off, the refinement reaches the minimum OpenCV's LM reaches:
// the same objective, so the same pose to 1e-8 (rad, m), far below the 0.3 px noise's effect.
TEST(ReprojectionRefiner, ReachesTheMinimumOfOpenCvsLevenbergMarquardt) {
  const Scene s = noisyScene();
  const cv::Vec3d r0 = s.rTrue + cv::Vec3d(0.01, -0.005, 0.004),
                  t0 = s.tTrue + cv::Vec3d(0.01, 0.0, -0.01);
  cv::Vec3d rLm = r0, tLm = t0;
  cv::solvePnPRefineLM(
      s.object, s.image, s.K, cv::noArray(), rLm, tLm,
      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-15));
  cv::Vec3d r = r0, t = t0;
  const int steps = refineReprojection(s.object, s.image, s.K, r, t);
  EXPECT_GT(steps, 0);
  EXPECT_LT(cv::norm(r - rLm), 1e-8);
  EXPECT_LT(cv::norm(t - tLm), 1e-8);
  // And it is better than the start by far: the start is several pixels off.
  std::vector<cv::Point2d> back;
  cv::projectPoints(s.object, r, t, s.K, cv::noArray(), back);
  double sum = 0.0;
  for (std::size_t i = 0; i < back.size(); ++i) sum += std::pow(cv::norm(back[i] - s.image[i]), 2);
  EXPECT_LT(std::sqrt(sum / static_cast<double>(back.size())), 0.5);  // ~0.3 px noise x sqrt(2)
}

// From a start 9 degrees and 15 cm off (a poor RANSAC model), the refinement
// still reaches OpenCV's minimum (1e-7: the looser start takes more of the 30 steps).
TEST(ReprojectionRefiner, FromAFarStartStillReachesTheMinimum) {
  const Scene s = noisyScene();
  const cv::Vec3d r0 = s.rTrue + cv::Vec3d(0.12, -0.08, 0.06),
                  t0 = s.tTrue + cv::Vec3d(0.10, -0.05, 0.10);
  cv::Vec3d rLm = r0, tLm = t0;
  cv::solvePnPRefineLM(
      s.object, s.image, s.K, cv::noArray(), rLm, tLm,
      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-15));
  cv::Vec3d r = r0, t = t0;
  refineReprojection(s.object, s.image, s.K, r, t, 30);
  EXPECT_LT(cv::norm(r - rLm), 1e-7);
  EXPECT_LT(cv::norm(t - tLm), 1e-7);
}

// At the minimum no step lowers the error: nothing moves.
TEST(ReprojectionRefiner, AtTheMinimumThePoseStaysPut) {
  const Scene s = noisyScene();
  cv::Vec3d r = s.rTrue, t = s.tTrue;
  refineReprojection(s.object, s.image, s.K, r, t, 50);
  const cv::Vec3d r1 = r, t1 = t;
  refineReprojection(s.object, s.image, s.K, r, t, 50);
  EXPECT_LT(cv::norm(r - r1), 1e-12);
  EXPECT_LT(cv::norm(t - t1), 1e-12);
}

TEST(ReprojectionRefiner, TooFewOrMismatchedPairsChangeNothing) {
  const Scene s = noisyScene();
  cv::Vec3d r = s.rTrue, t = s.tTrue;
  const std::vector<cv::Point3d> two(s.object.begin(), s.object.begin() + 2);
  const std::vector<cv::Point2d> twoPx(s.image.begin(), s.image.begin() + 2);
  EXPECT_EQ(refineReprojection(two, twoPx, s.K, r, t), 0);
  EXPECT_EQ(refineReprojection(s.object, twoPx, s.K, r, t), 0);
  EXPECT_EQ(r, s.rTrue);
  EXPECT_EQ(t, s.tTrue);
}

}  // namespace
}  // namespace reftrack
