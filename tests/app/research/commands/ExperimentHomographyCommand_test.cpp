#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "TestPaths.hpp"
#include "app/commands/CommandTestSupport.hpp"
#include "engine/features/SyntheticImages.hpp"

using namespace reftrack::test;

TEST(ExperimentHomographyCommand, PrintsTablesAndWritesPlots) {
  const auto dir = freshTempDir("ExperimentHomographyCommand");
  const auto r = runReftrack(
      "experiment-homography --frames 10 --trials 2 --max-angle 20 "
      "--step 10 --out " +
          (dir / "plots").string(),
      dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("10/10"), std::string::npos) << r.out;  // every static frame registered
  EXPECT_NE(r.out.find("pure rotation sweep"), std::string::npos);
  for (const char* png :
       {"static_centre_deviation.png", "rotation_annotation_error.png", "rotation_success.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / "plots" / png)) << png;
  EXPECT_EQ(runReftrack("experiment-homography --experiment nope", dir).exitCode, 2);
  EXPECT_EQ(runReftrack("experiment-homography --step 0", dir).exitCode, 2);
}

// The pairs experiment on a folder of one pair (a textured image and a tilted view of it, its
// homography as text): scored over the overlap by default, at img1's corners on request; it
// prints what reftrack's registration check compared and the cost beside SIFT's.
TEST(ExperimentHomographyCommand, ScoresPairsOverTheOverlapByDefault) {
  const auto dir = freshTempDir("ExperimentHomographyCommandPairs");
  const cv::Size size(320, 240);
  const cv::Mat reference = texturedImage(size, 71);
  const cv::Matx33d H = tiltedView(size, 20.0, 0.9, 10.0);
  std::filesystem::create_directories(dir / "pair");
  cv::imwrite((dir / "pair" / "img1.png").string(), reference);
  cv::imwrite((dir / "pair" / "img2.png").string(), withNoise(warpedBy(reference, H), 2.0, 3));
  std::ofstream((dir / "pair" / "H1to2p").string())
      << H(0, 0) << ' ' << H(0, 1) << ' ' << H(0, 2) << '\n'
      << H(1, 0) << ' ' << H(1, 1) << ' ' << H(1, 2) << '\n'
      << H(2, 0) << ' ' << H(2, 1) << ' ' << H(2, 2) << '\n';
  const std::string pairs =
      "experiment-homography --experiment pairs --data " + (dir / "pair").string();
  const auto overlap = runReftrack(pairs, dir);
  ASSERT_EQ(overlap.exitCode, 0) << overlap.err;
  EXPECT_NE(overlap.out.find("error: mean over the reference points the frame sees"),
            std::string::npos)
      << overlap.out;
  EXPECT_NE(overlap.out.find("pair                   reftrack         1/1"), std::string::npos)
      << overlap.out;
  EXPECT_NE(overlap.out.find("passed: "), std::string::npos) << overlap.out;
  EXPECT_NE(overlap.out.find("in the inliers' region"), std::string::npos) << overlap.out;
  EXPECT_NE(overlap.out.find("cost beside SIFT's"), std::string::npos) << overlap.out;
  const auto corners = runReftrack(pairs + " --metric corners --no-peers", dir);
  ASSERT_EQ(corners.exitCode, 0) << corners.err;
  EXPECT_NE(corners.out.find("error: mean at the reference image's four corners"),
            std::string::npos)
      << corners.out;
  EXPECT_EQ(corners.out.find("cost beside SIFT's"), std::string::npos);  // no peers, no SIFT
}
