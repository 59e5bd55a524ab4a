#include "engine/config/RelocalisationParams.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "TestPaths.hpp"
#include "engine/config/ParamsTestSupport.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/reference/ReferencePreparer.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(RelocalisationParams, RoundTrip) {
  RelocalisationParams in;
  in.enabled = false;
  in.keypoints = "sift";
  in.featuresPerFrame = 700;
  in.featuresPerReference = 1500;
  in.referenceFinerLevels = 5;
  in.frameFinerLevels = 2;
  in.ratio = 0.7;
  in.referencesToMatch = 5;
  in.ransacIterations = 150;
  in.reprojectionPx = 1.5;
  in.minInliers = 25;
  in.minInlierRatio = 0.3;
  in.attemptEveryFrames = 3;
  in.minInlierCells = 5;
  in.maxRotationSigmaDeg = 0.7;
  in.maxPositionSigmaRatio = 0.05;
  in.triangulationPx = 0.8;
  in.minParallaxDeg = 2.0;
  RelocalisationParams out;
  roundTrip(in, out);
  EXPECT_FALSE(out.enabled);
  EXPECT_EQ(out.keypoints, "sift");
  EXPECT_EQ(out.featuresPerFrame, 700);
  EXPECT_EQ(out.featuresPerReference, 1500);
  EXPECT_EQ(out.referenceFinerLevels, 5);
  EXPECT_EQ(out.frameFinerLevels, 2);
  EXPECT_DOUBLE_EQ(out.ratio, 0.7);
  EXPECT_EQ(out.referencesToMatch, 5);
  EXPECT_EQ(out.ransacIterations, 150);
  EXPECT_DOUBLE_EQ(out.reprojectionPx, 1.5);
  EXPECT_EQ(out.minInliers, 25);
  EXPECT_DOUBLE_EQ(out.minInlierRatio, 0.3);
  EXPECT_EQ(out.attemptEveryFrames, 3);
  EXPECT_EQ(out.minInlierCells, 5);
  EXPECT_DOUBLE_EQ(out.maxRotationSigmaDeg, 0.7);
  EXPECT_DOUBLE_EQ(out.maxPositionSigmaRatio, 0.05);
  EXPECT_DOUBLE_EQ(out.triangulationPx, 0.8);
  EXPECT_DOUBLE_EQ(out.minParallaxDeg, 2.0);
}

TEST(RelocalisationParams, MissingKeysKeepDefaults) {
  RelocalisationParams p;
  p.read(parseYaml("relocalisation:\n  min_inliers: 40\n")["relocalisation"]);
  EXPECT_EQ(p.minInliers, 40);
  EXPECT_EQ(p.keypoints, RelocalisationParams{}.keypoints);
  EXPECT_EQ(p.featuresPerFrame, RelocalisationParams{}.featuresPerFrame);
}

// The parameter-file fuzz target's seeds written from the defaults (tests/fuzz/corpus/params_file)
// carry the finer-level keys and load through their readers (which refuse unknown keys).
TEST(RelocalisationParams, FuzzSeedsCarryTheFinerLevelKeys) {
  const auto seeds = sourceDir() / "tests" / "fuzz" / "corpus" / "params_file";
  for (const char* name : {"tracker_defaults.yml", "preparation_defaults.yml"}) {
    const YamlNode root = readConfigFile(seeds / name, name);
    for (const char* key : {"reference_finer_levels", "frame_finer_levels"})
      EXPECT_TRUE(root["relocalisation"][key].integer()) << name << ": relocalisation." << key;
  }
  EXPECT_EQ(TrackerParams::load(seeds / "tracker_defaults.yml").relocalisation.frameFinerLevels,
            RelocalisationParams{}.frameFinerLevels);
  EXPECT_EQ(ReferencePreparerParams::load(seeds / "preparation_defaults.yml")
                .relocalisation.referenceFinerLevels,
            RelocalisationParams{}.referenceFinerLevels);
}

TEST(RelocalisationParams, KeypointCountsScaleWithTheImageArea) {
  RelocalisationParams p;
  p.featuresPerFrame = 1000;
  p.featuresPerReference = 2000;
  EXPECT_EQ(p.featuresPerFrameFor({640, 480}), 1000);
  EXPECT_EQ(p.featuresPerFrameFor({320, 240}), 250);
  EXPECT_EQ(p.featuresPerReferenceFor({1280, 960}), 8000);
}

TEST(RelocalisationParams, EveryBadFieldIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  using P = RelocalisationParams;
  const std::vector<std::pair<std::string, std::function<void(P&)>>> cases = {
      {"relocalisation.keypoints", [](P& p) { p.keypoints = "surf"; }},
      {"relocalisation.features_per_frame", [](P& p) { p.featuresPerFrame = 0; }},
      {"relocalisation.features_per_reference", [](P& p) { p.featuresPerReference = -5; }},
      {"relocalisation.reference_finer_levels", [](P& p) { p.referenceFinerLevels = -1; }},
      {"relocalisation.reference_finer_levels", [](P& p) { p.referenceFinerLevels = 9; }},
      {"relocalisation.frame_finer_levels", [](P& p) { p.frameFinerLevels = -2; }},
      {"relocalisation.ratio", [&](P& p) { p.ratio = nan; }},
      {"relocalisation.ratio", [](P& p) { p.ratio = 1.5; }},
      {"relocalisation.references_to_match", [](P& p) { p.referencesToMatch = 0; }},
      {"relocalisation.ransac_iterations", [](P& p) { p.ransacIterations = 0; }},
      {"relocalisation.reprojection_px", [](P& p) { p.reprojectionPx = 0.0; }},
      {"relocalisation.min_inliers", [](P& p) { p.minInliers = 3; }},
      {"relocalisation.min_inlier_ratio", [](P& p) { p.minInlierRatio = -0.1; }},
      {"relocalisation.attempt_every_frames", [](P& p) { p.attemptEveryFrames = 0; }},
      {"relocalisation.min_inlier_cells", [](P& p) { p.minInlierCells = 17; }},
      {"relocalisation.max_rotation_sigma_deg", [](P& p) { p.maxRotationSigmaDeg = -1.0; }},
      {"relocalisation.max_position_sigma_ratio", [&](P& p) { p.maxPositionSigmaRatio = nan; }},
      {"relocalisation.triangulation_px", [&](P& p) { p.triangulationPx = nan; }},
      {"relocalisation.min_parallax_deg", [](P& p) { p.minParallaxDeg = -1.0; }},
  };
  for (const auto& [field, mutate] : cases) {
    P p;
    mutate(p);
    EXPECT_NE(errorMessage([&] { p.check(); }).find(field), std::string::npos) << field;
  }
  // read() checks too: a bad value in a file is reported with its line and key.
  P p;
  const std::string ratio =
      errorMessage([&] { p.read(parseYaml("relocalisation:\n  ratio: 3\n")["relocalisation"]); });
  EXPECT_EQ(ratio.rfind("line 2: parameter 'relocalisation.ratio' must lie in", 0), 0u) << ratio;
  EXPECT_NE(errorMessage([&] {
              p.read(parseYaml("relocalisation:\n  keypoints: 4\n")["relocalisation"]);
            }).find("relocalisation.keypoints"),
            std::string::npos);
}
