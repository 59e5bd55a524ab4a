#include "app/research/homography/HomographyPairsExperiment.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <opencv2/imgcodecs.hpp>

#include "TestPaths.hpp"
#include "app/research/homography/HomographyGroundTruth.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/SyntheticImages.hpp"
#include "engine/homography/HomographyDlt.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(HomographyPairsExperiment, SyntheticViewsHaveTheStatedGeometry) {
  const cv::Size size(800, 600);
  const cv::Point2d centre(399.5, 299.5);
  // No tilt, scale 1, no roll: the identity.
  EXPECT_LT(cv::norm(syntheticViewHomography(size, 0, 0, 1, 0) - cv::Matx33d::eye()), 1e-12);
  // Zoom 2 with a 90 degree roll about the centre: (x, y) offsets become 2 (-y, x) or 2 (y, -x).
  const cv::Matx33d zoom = syntheticViewHomography(size, 0, 0, 2, 90);
  EXPECT_LT(cv::norm(transferPoint(zoom, centre) - centre), 1e-9);
  const cv::Point2d right = transferPoint(zoom, centre + cv::Point2d(10, 0)) - centre;
  EXPECT_NEAR(std::hypot(right.x, right.y), 20.0, 1e-9);
  EXPECT_NEAR(std::abs(right.y), 20.0, 1e-9);
  // A tilt keeps the centre and foreshortens one side more than the other (perspective).
  const cv::Matx33d tilt = syntheticViewHomography(size, 40, 0, 1, 0);
  EXPECT_LT(cv::norm(transferPoint(tilt, centre) - centre), 1e-9);
  const double up = cv::norm(transferPoint(tilt, centre + cv::Point2d(0, -200)) - centre);
  const double down = cv::norm(transferPoint(tilt, centre + cv::Point2d(0, 200)) - centre);
  EXPECT_GT(std::abs(up - down), 10.0);
  EXPECT_LT(std::max(up, down), 200.0 + 1e-9 + 100.0);
}

TEST(HomographyPairsExperiment, SynthesisedViewsAgreeWithTheirHomography) {
  const cv::Size size(640, 480);
  const cv::Mat image = test::texturedImage(size, 51);
  for (const cv::Matx33d& H : {syntheticViewHomography(size, 30, 90, 1.2, 20),
                               syntheticViewHomography(size, 0, 0, 0.6, 200)}) {
    const cv::Mat view = synthesiseView(image, H, 0.0, 1);
    ASSERT_EQ(view.size(), size);
    // Sampled back through H^-1 (bilinear), the view reproduces the image where it sees it: a
    // wrong pixel-centre convention (0.25-0.5 px) would show as a mean difference several
    // grey levels larger on this sharp-edged texture.
    cv::Mat back;
    cv::warpPerspective(view, back, H, size, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP);
    cv::Mat seen;
    cv::warpPerspective(cv::Mat(size, CV_8UC1, cv::Scalar(255)), seen, H, size, cv::INTER_NEAREST);
    cv::erode(seen, seen, cv::Mat(), cv::Point(-1, -1), 4);
    cv::warpPerspective(seen, seen, H, size, cv::INTER_NEAREST | cv::WARP_INVERSE_MAP);
    cv::Mat diff;
    cv::absdiff(back, image, diff);
    ASSERT_GT(cv::countNonZero(seen), 10000);
    EXPECT_LT(cv::mean(diff, seen)[0], 6.0);
  }
}

TEST(HomographyPairsExperiment, BuildsAndRegistersPairsOfASequenceFolder) {
  // A made-up sequence: img1 and a real-style pair img2 with its H1to2p.xml.
  const auto dir = test::freshTempDir("pairs_experiment");
  const cv::Size size(640, 480);
  const cv::Mat img1 = test::texturedImage(size, 52);
  const cv::Matx33d H12(1.02, 0.03, -8, -0.02, 0.99, 5, 1e-5, 0, 1);
  std::filesystem::create_directories(dir / "seq");
  cv::imwrite((dir / "seq" / "img1.png").string(), img1);
  cv::imwrite((dir / "seq" / "img2.png").string(), test::warpedBy(img1, H12));
  {
    cv::FileStorage fs((dir / "seq" / "H1to2p.xml").string(), cv::FileStorage::WRITE);
    fs << "H12" << cv::Mat(H12);
  }
  // Real pairs only by default; the synthesised views on request.
  ASSERT_EQ(buildHomographyPairs(dir, 2.0, 1).size(), 1u);
  const std::vector<HomographyPair> pairs = buildHomographyPairs(dir, 2.0, 1, true);
  ASSERT_EQ(pairs.size(), 19u);  // 1 real + 10 viewpoint + 8 zoom-rotation
  EXPECT_TRUE(pairs[0].real);
  EXPECT_EQ(pairs[0].kind, dir.filename().string());
  EXPECT_LT(cv::norm(pairs[0].truth - H12), 1e-12);
  int viewpoint = 0, zoom = 0;
  for (const HomographyPair& p : pairs) {
    EXPECT_EQ(p.sequence, p.real ? "seq" : "seq-views");
    EXPECT_EQ(p.frame.size(), size);
    viewpoint += p.kind == "viewpoint" ? 1 : 0;
    zoom += p.kind == "zoom-rotation" ? 1 : 0;
  }
  EXPECT_EQ(viewpoint, 10);
  EXPECT_EQ(zoom, 8);

  PairsOptions o;
  o.dataDir = dir;
  o.broadViews = true;
  const PairsResult r = runPairsExperiment(o);
  ASSERT_EQ(r.methods.size(), 5u);
  EXPECT_EQ(r.methods[0].name, "reftrack");
  int registered = 0, wrong = 0;
  for (const PairsMethod& m : r.methods) ASSERT_EQ(m.outcomes.size(), pairs.size());
  for (const PairOutcome& o2 : r.methods[0].outcomes) {
    if (!o2.found) continue;
    (o2.overlapErrorPx <= 3.0 ? registered : wrong) += 1;  // over what the view sees
  }
  // The tracker never returns a wrong homography and registers nearly all of these views of
  // an evenly textured image (tilts to 60 degrees and 0.5-3.5x zooms included; 2 misses allowed).
  EXPECT_EQ(wrong, 0);
  EXPECT_GE(registered, 17);

  // Only the sets asked for; a set that is not there is an error.
  o.onlySets = {"seq"};
  EXPECT_EQ(runPairsExperiment(o).pairs.size(), 1u);
  o.onlySets = {"graf-sim"};
  EXPECT_THROW(runPairsExperiment(o), Error);
  EXPECT_EQ(buildHomographyPairs(dir / "seq", 2.0, 1).size(), 1u);  // a sequence folder itself
  EXPECT_THROW(buildHomographyPairs(dir / "missing", 2.0, 1), Error);
}

// The repeated-texture sets of the experiment (issue 26): the simulated brick wall (reference
// 1000x700, frames 880x680 from another camera, 20-60 degrees) and the tiles (800x600 -> 640x480,
// zoom and rotation), registered cold by the tracker and the OpenCV peers in one run. The
// tracker reports no registration more than 3 px off on either set and registers more pairs
// within 3 px than each peer; of the brick wall's 5 views at least 4 (the target is 2).
// Errors: mean over the reference points the view sees (overlapErrorPx).
// Measured (walls rendered with 2 x 2 rays per pixel to keep the test short): reftrack all 10
// within 2.6 px; SIFT 5, AKAZE 5, ORB 3, with ORB 15.9 and 29.6 px off on two tiles views.
TEST(HomographyPairsExperiment, RegistersTheRepeatedTextureSetsWithoutAWrongRegistration) {
  const auto dir = test::freshTempDir("pairs_repeated_texture");
  std::filesystem::create_directories(dir / "seq");
  cv::imwrite((dir / "seq" / "img1.png").string(), test::texturedImage({320, 240}, 53));
  PairsOptions o;
  o.dataDir = dir;
  o.hardSets = true;
  o.onlySets = {"wall-sim", "tiles-sim"};
  o.wallSupersample = 2;
  const PairsResult r = runPairsExperiment(o);
  ASSERT_EQ(r.pairs.size(), 10u);
  ASSERT_EQ(r.methods[0].name, "reftrack");
  int wall = 0, tiles = 0;
  std::vector<int> within(r.methods.size(), 0);
  for (size_t m = 0; m < r.methods.size(); ++m)
    for (const PairOutcome& o2 : r.methods[m].outcomes)
      within[m] += o2.found && o2.overlapErrorPx <= 3.0 ? 1 : 0;
  for (size_t i = 0; i < r.pairs.size(); ++i) {
    const PairOutcome& own = r.methods[0].outcomes[i];
    std::printf("%s %s: reftrack %s %.2f px, %.1f ms", r.pairs[i].sequence.c_str(),
                r.pairs[i].label.c_str(), own.found ? "found" : "lost",
                own.found ? own.overlapErrorPx : -1.0, own.milliseconds);
    for (size_t m = 2; m < r.methods.size(); ++m)
      std::printf("; %s %.2f", r.methods[m].name.c_str(),
                  r.methods[m].outcomes[i].found ? r.methods[m].outcomes[i].overlapErrorPx : -1.0);
    std::printf("\n");
    if (!own.found) continue;
    EXPECT_LE(own.overlapErrorPx, 3.0) << r.pairs[i].sequence << " " << r.pairs[i].label;
    (r.pairs[i].sequence == "wall-sim" ? wall : tiles) += own.overlapErrorPx <= 3.0 ? 1 : 0;
  }
  EXPECT_GE(wall, 4);
  EXPECT_GE(tiles, 4);
  for (size_t m = 2; m < r.methods.size(); ++m)
    EXPECT_GT(within[0], within[m]) << r.methods[m].name;
}

// The eight real Oxford sets (../shared/data: oxford-photometric and oxford-viewpoint, 40 pairs
// img1 -> imgN), registered cold by reftrack alone and scored at img1's corners against the
// given homographies. Measured (experiment-homography --experiment pairs --data ../shared/data):
// 31 within 3 px; the nine others are 3.2-10.2 px from the given H, where the three OpenCV peers
// are too (within 1.3 px of reftrack) and ECC moves the given H by as much (next test). The bound
// on every returned H (12 px) leaves 1.8 px above the largest, boat 1->6 (10.2 px); the count
// (31) is the one measured: any pair lost or moved off fails the test.
TEST(HomographyPairsExperiment, RegistersTheRealOxfordPairsWhereTheirHomographiesHold) {
  const auto data = test::sharedDataDir();
  if (!data || !std::filesystem::exists(*data / "oxford-viewpoint" / "wall" / "img1.png"))
    GTEST_SKIP() << "../shared/data with the Oxford sets not present";
  PairsOptions o;
  o.dataDir = *data;
  o.onlySets = {"bikes", "leuven", "trees", "ubc", "bark", "boat", "graf", "wall"};
  o.peers = false;
  const PairsResult r = runPairsExperiment(o);
  ASSERT_EQ(r.pairs.size(), 40u);
  int within3 = 0;
  for (size_t i = 0; i < r.pairs.size(); ++i) {
    const PairOutcome& own = r.methods[0].outcomes[i];
    ASSERT_TRUE(own.found) << r.pairs[i].sequence << " " << r.pairs[i].label << ": " << own.failure;
    EXPECT_LT(own.cornerErrorPx, 12.0) << r.pairs[i].sequence << " " << r.pairs[i].label;
    within3 += own.cornerErrorPx <= 3.0 ? 1 : 0;
  }
  EXPECT_GE(within3, 31);
}

// The check of the given homographies: OpenCV's ECC started from them leaves ubc 1->3's (JPEG
// only, a flat print) where it is (measured 0.01 px at img1's corners) and moves boat 1->6's (a
// harbour, not a plane, seen 2.8x zoomed) by 10.9 px — to within 1 px of where reftrack,
// SIFT, AKAZE and ORB all register it (each 9.8-10.9 px from the given H).
TEST(HomographyPairsExperiment, EccShowsWhereTheGivenHomographyIsOff) {
  const auto data = test::sharedDataDir();
  if (!data || !std::filesystem::exists(*data / "oxford-viewpoint" / "boat" / "img6.png"))
    GTEST_SKIP() << "../shared/data with the Oxford sets not present";
  PairsOptions o;
  o.dataDir = *data;
  o.onlySets = {"ubc", "boat"};
  o.peers = false;
  const PairsResult given = runPairsExperiment(o);
  o.refineTruth = true;
  const PairsResult refined = runPairsExperiment(o);
  ASSERT_EQ(refined.pairs.size(), 10u);
  for (size_t i = 0; i < refined.pairs.size(); ++i) {
    const std::string name = refined.pairs[i].sequence + " " + refined.pairs[i].label;
    const RefinedTruth& t = refined.truthChecks[i];
    ASSERT_TRUE(t.converged) << name;
    if (name == "ubc 1->3") {
      EXPECT_LT(t.movedPx, 0.1);
    }
    if (name == "boat 1->6") {
      EXPECT_GT(t.movedPx, 8.0);
      EXPECT_GT(given.methods[0].outcomes[i].cornerErrorPx, 8.0);
      EXPECT_LT(refined.methods[0].outcomes[i].cornerErrorPx, 1.5);
    }
  }
}
