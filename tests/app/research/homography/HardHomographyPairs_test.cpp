#include "app/research/homography/HardHomographyPairs.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "TestPaths.hpp"
#include "app/research/homography/HomographyPairsExperiment.hpp"
#include "engine/features/ImagePyramid.hpp"
#include "engine/homography/RegistrationVerifier.hpp"

using namespace reftrack;
using namespace reftrack::app;

// Without the Oxford images only the simulated sets are built: the brick wall (reference
// 1000x700, frames 880x680 from another camera, 20-60 degrees) and the tiles (800x600 -> 640x480).
// Each truth is exact for the units' faces (the joints are recessed): the registration check,
// which correlates the reference warped by it with the frame, passes every one. Written as
// Oxford-style folders, the sets read back as real pairs of other sizes.
TEST(HardHomographyPairs, BuildsTheSimulatedSetsWithExactHomographies) {
  const auto empty = test::freshTempDir("hard_pairs_no_data");
  // 2 x 2 rays per pixel instead of 4 x 4: a quarter of the rendering time.
  const std::vector<HomographyPair> pairs = buildHardHomographyPairs(empty, 2.0, 1, 2);
  ASSERT_EQ(pairs.size(), 10u);
  for (size_t i = 0; i < pairs.size(); ++i) {
    const HomographyPair& p = pairs[i];
    const bool wall = i < 5;
    EXPECT_EQ(p.sequence, wall ? "wall-sim" : "tiles-sim");
    if (wall) {
      EXPECT_EQ(p.kind, "viewpoint");
    }
    EXPECT_EQ(p.reference.size(), wall ? cv::Size(1000, 700) : cv::Size(800, 600));
    EXPECT_EQ(p.frame.size(), wall ? cv::Size(880, 680) : cv::Size(640, 480));
    EXPECT_EQ(p.frame.type(), CV_8UC1);
    const RegistrationCheck c =
        RegistrationVerifier(p.reference).check(ImagePyramid(p.frame), p.truth);
    EXPECT_TRUE(c.passed) << p.sequence << " " << p.label << ": " << c.failure;
  }
  EXPECT_EQ(hardPairSetNames().size(), 5u);

  const auto dir = test::freshTempDir("hard_pairs_saved");
  saveHomographyPairs(pairs, dir);
  const std::vector<HomographyPair> back = buildHomographyPairs(dir, 0.0, 1);
  int real = 0;
  for (const HomographyPair& p : back) {
    if (!p.real) continue;
    ++real;
    // imgN of a set is its (N - 1)-th pair.
    const int n = std::stoi(p.label.substr(3)) - 2;
    const size_t original = static_cast<size_t>((p.sequence == "wall-sim" ? 0 : 5) + n);
    EXPECT_EQ(p.frame.size(), pairs[original].frame.size()) << p.sequence << " " << p.label;
    EXPECT_LT(cv::norm(p.truth - pairs[original].truth), 1e-9) << p.sequence << " " << p.label;
  }
  EXPECT_EQ(real, 10);
}
