#include "engine/config/TrackerParams.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "TestPaths.hpp"
#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

namespace {
std::filesystem::path writeText(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return file;
}
}  // namespace

TEST(TrackerParams, SaveLoadRoundTripsEverySection) {
  const auto dir = freshTempDir("TrackerParams_roundtrip");
  TrackerParams in;
  in.mode = TrackingMode::Homography;
  in.corners.countAt320x240 = 60;
  in.correlation.minScore = 0.75;
  in.ransac.maxIterations = 90;
  in.homography.guidedSearchHalfSizePx = 5;
  in.wideBaseline.dx = 12;
  in.pose.estimator = PoseEstimatorKind::Standard;
  in.relocalisation.keypoints = "akaze";
  in.relocalisation.minInliers = 31;
  in.references.switchAfterFrames = 6;
  in.save(dir / "params.yml");
  const TrackerParams out = TrackerParams::load(dir / "params.yml");
  EXPECT_EQ(out.mode, TrackingMode::Homography);
  EXPECT_EQ(out.corners.countAt320x240, 60);
  EXPECT_DOUBLE_EQ(out.correlation.minScore, 0.75);
  EXPECT_EQ(out.ransac.maxIterations, 90);
  EXPECT_DOUBLE_EQ(out.homography.guidedSearchHalfSizePx, 5);
  EXPECT_EQ(out.wideBaseline.dx, 12);
  EXPECT_EQ(out.pose.estimator, PoseEstimatorKind::Standard);
  EXPECT_EQ(out.relocalisation.keypoints, "akaze");
  EXPECT_EQ(out.relocalisation.minInliers, 31);
  EXPECT_EQ(out.references.switchAfterFrames, 6);
  // Only the final file remains (atomic write leaves no temporary behind).
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator()),
            1);
}

TEST(TrackerParams, MissingKeysKeepDefaults) {
  const auto dir = freshTempDir("TrackerParams_defaults");
  const TrackerParams p =
      TrackerParams::load(writeText(dir / "p.yml", "%YAML:1.0\nransac:\n  max_iterations: 20\n"));
  EXPECT_EQ(p.ransac.maxIterations, 20);
  EXPECT_EQ(p.ransac.earlyAcceptMinIterations, 15);
  EXPECT_EQ(p.mode, TrackingMode::SixDof);
  EXPECT_EQ(p.corners.countAt320x240, 55);
}

TEST(TrackerParams, ErrorsNameFileAndKey) {
  const auto dir = freshTempDir("TrackerParams_errors");
  const auto bad = [&](const std::string& name, const std::string& body) {
    const auto file = writeText(dir / name, "%YAML:1.0\n" + body);
    return errorMessage([&] { TrackerParams::load(file); });
  };
  EXPECT_NE(bad("mode.yml", "mode: stereo\n").find("'mode'"), std::string::npos);
  EXPECT_NE(bad("nan.yml", "correlation:\n  min_score: .nan\n").find("correlation.min_score"),
            std::string::npos);
  EXPECT_NE(bad("type.yml", "corners:\n  count: lots\n").find("corners.count"), std::string::npos);
  EXPECT_NE(bad("range.yml", "ransac:\n  min_inlier_ratio: 3\n").find("ransac.min_inlier_ratio"),
            std::string::npos);
  EXPECT_NE(bad("section.yml", "pose: 3\n").find("'pose'"), std::string::npos);
  EXPECT_NE(
      bad("reloc.yml", "relocalisation:\n  min_inliers: 2\n").find("relocalisation.min_inliers"),
      std::string::npos);
  EXPECT_NE(
      bad("kind.yml", "relocalisation:\n  keypoints: brisk\n").find("relocalisation.keypoints"),
      std::string::npos);
  EXPECT_NE(bad("range.yml", "ransac:\n  min_inlier_ratio: 3\n").find("range.yml"),
            std::string::npos);
  EXPECT_NE(errorMessage([&] { TrackerParams::load(dir / "absent.yml"); }).find("does not exist"),
            std::string::npos);
  EXPECT_NE(bad("garbage.yml", "[unclosed: {\n").find("garbage.yml"), std::string::npos);
}

TEST(TrackerParams, ModeNames) {
  EXPECT_EQ(parseTrackingMode("6dof"), TrackingMode::SixDof);
  EXPECT_EQ(parseTrackingMode("homography"), TrackingMode::Homography);
  EXPECT_THROW(parseTrackingMode("affine"), Error);
}

TEST(TrackerParams, UnknownKeysAndSectionsNameTheNearestKnownOne) {
  const auto dir = freshTempDir("TrackerParams_strict");
  const auto bad = [&](const std::string& body) {
    const auto file = writeText(dir / "p.yml", "%YAML:1.0\n" + body);
    return errorMessage([&] { TrackerParams::load(file); });
  };
  EXPECT_EQ(bad("ransac: {iterations: 200}\n"),
            "parameter file '" + (dir / "p.yml").string() +
                "': line 2: ransac.iterations: unknown key — did you mean ransac.max_iterations?");
  EXPECT_NE(bad("ransca:\n  max_iterations: 200\n")
                .find("ransca: unknown section — did you mean ransac?"),
            std::string::npos);
  EXPECT_NE(bad("mod: homography\n").find("mod: unknown key — did you mean mode?"),
            std::string::npos);
  EXPECT_NE(bad("relocalisation:\n  enable: false\n")
                .find("relocalisation.enable: unknown key — did you mean relocalisation.enabled?"),
            std::string::npos);
  // The viewer's overlay section shares the file; its keys are the viewer's to check.
  EXPECT_EQ(bad("overlay:\n  size: 0.3\n"), "(no error)");
}

TEST(TrackerParams, ReadsAHandWrittenFileWithoutTheYamlDirective) {
  const auto dir = freshTempDir("TrackerParams_noDirective");
  const TrackerParams p = TrackerParams::load(
      writeText(dir / "p.yml", "# mine\nmode: homography\nransac: {max_iterations: 33}\n"));
  EXPECT_EQ(p.mode, TrackingMode::Homography);
  EXPECT_EQ(p.ransac.maxIterations, 33);
}

// The targets: ordinary YAML (a flow map, a trailing comment, an anchor and an alias) is
// read and used; a misspelt key in a flow map is refused naming its line and the right key.
TEST(TrackerParams, ReadsOrdinaryYamlAndRefusesAMisspeltKeyWithItsLine) {
  const auto dir = freshTempDir("TrackerParams_ordinaryYaml");
  const TrackerParams p = TrackerParams::load(writeText(dir / "p.yml",
                                                        "mode: 6dof   # the default, said aloud\n"
                                                        "ransac: {max_iterations: &iterations 80, "
                                                        "seed: 3}  # flow map\n"
                                                        "relocalisation:\n"
                                                        "  # an alias of the RANSAC cap\n"
                                                        "  ransac_iterations: *iterations\n"));
  EXPECT_EQ(p.ransac.maxIterations, 80);
  EXPECT_EQ(p.ransac.seed, 3);
  EXPECT_EQ(p.relocalisation.ransacIterations, 80);
  EXPECT_NE(TrackerParams{}.relocalisation.ransacIterations, 80);  // it was read, not a default

  const auto file = writeText(dir / "typo.yml",
                              "mode: 6dof\n# tuned for the desk\nransac: {max_iteratons: 80}\n");
  EXPECT_EQ(
      errorMessage([&] { TrackerParams::load(file); }),
      "parameter file '" + file.string() +
          "': line 3: ransac.max_iteratons: unknown key — did you mean ransac.max_iterations?");
  // A bad value names its line and key too.
  const auto value = writeText(dir / "value.yml", "ransac:\n  seed: 1\n  max_iterations: -5\n");
  EXPECT_EQ(errorMessage([&] { TrackerParams::load(value); }),
            "parameter file '" + value.string() +
                "': line 3: parameter 'ransac.max_iterations' must lie in [1, 1000000], got -5");
}

TEST(TrackerParams, ParsesYamlOrJsonText) {
  EXPECT_EQ(
      TrackerParams::parse("{\"ransac\": {\"max_iterations\": 90}}", "dict").ransac.maxIterations,
      90);
  EXPECT_EQ(errorMessage([] { TrackerParams::parse("{\"ransac\": {\"seeds\": 1}}", "dict"); }),
            "dict: line 1: ransac.seeds: unknown key — did you mean ransac.seed?");
  EXPECT_EQ(TrackerParams::parse("", "empty").ransac.maxIterations,
            TrackerParams{}.ransac.maxIterations);
}

// engine/README.md's example parameter file ("## Parameters"), read as written.
TEST(TrackerParams, ReadsTheReadmesExample) {
  const std::string readme = readTextFile(sourceDir() / "engine" / "README.md");
  const std::size_t section = readme.find("\n## Parameters\n");
  ASSERT_NE(section, std::string::npos);
  const std::size_t start = readme.find("```yaml\n", section);
  ASSERT_NE(start, std::string::npos);
  const std::size_t end = readme.find("```", start + 8);
  const TrackerParams p =
      TrackerParams::parse(readme.substr(start + 8, end - start - 8), "README example");
  EXPECT_EQ(p.mode, TrackingMode::SixDof);
  EXPECT_EQ(p.ransac.maxIterations, 80);
  EXPECT_EQ(p.ransac.seed, 3);
  EXPECT_EQ(p.relocalisation.ransacIterations, 80);
}

// The keys main added in issue 24 (pose.map_point_sd_scale replacing the bool
// pose.map_point_uncertainty, relocalisation.min_distinctive_inliers, wide_baseline's frame-side
// alignment) are read by the YAML reader, in flow or block style, and a bad value names its line.
TEST(TrackerParams, ReadsTheRealFootageKeysWithTheirLines) {
  const TrackerParams defaults;
  EXPECT_DOUBLE_EQ(defaults.pose.mapPointSdScale, 0.5);
  EXPECT_FALSE(defaults.pose.estimateRollingShutter);
  EXPECT_EQ(defaults.relocalisation.keypoints, "sift");
  EXPECT_EQ(defaults.relocalisation.minDistinctiveInliers, 8);
  EXPECT_FALSE(defaults.wideBaseline.alignFrameSide);
  EXPECT_EQ(defaults.wideBaseline.alignHalfWindow, 7);

  const TrackerParams p = TrackerParams::parse(
      "pose: {map_point_sd_scale: 0.25, estimate_rolling_shutter: true}  # flow\n"
      "relocalisation:\n"
      "  keypoints: orb\n"
      "  min_distinctive_inliers: 5\n"
      "wide_baseline: {align_frame_side: true, align_half_window: 4}\n",
      "text");
  EXPECT_DOUBLE_EQ(p.pose.mapPointSdScale, 0.25);
  EXPECT_TRUE(p.pose.estimateRollingShutter);
  EXPECT_EQ(p.relocalisation.keypoints, "orb");
  EXPECT_EQ(p.relocalisation.minDistinctiveInliers, 5);
  EXPECT_TRUE(p.wideBaseline.alignFrameSide);
  EXPECT_EQ(p.wideBaseline.alignHalfWindow, 4);

  EXPECT_EQ(errorMessage([] {
              TrackerParams::parse("mode: 6dof\npose:\n  map_point_uncertainty: true\n", "text");
            }),
            "text: line 3: pose.map_point_uncertainty: unknown key — did you mean "
            "pose.map_point_sd_scale?");
  EXPECT_EQ(
      errorMessage(
          [] { TrackerParams::parse("wide_baseline:\n  align_half_window: 40\n", "text"); }),
      "text: line 2: parameter 'wide_baseline.align_half_window' must lie in [1, 32], got 40");
  const std::string notANumber = errorMessage(
      [] { TrackerParams::parse("relocalisation: {min_distinctive_inliers: many}\n", "text"); });
  EXPECT_EQ(notANumber.rfind("text: line 1: ", 0), 0u) << notANumber;
  EXPECT_NE(notANumber.find("relocalisation.min_distinctive_inliers"), std::string::npos)
      << notANumber;
}

// The parameter-file fuzz target's seed of the defaults (tests/fuzz/corpus/params_file) is what
// save() writes today, so the fuzzer starts from every key the reader knows.
TEST(TrackerParams, TheFuzzSeedOfTheDefaultsIsWhatSaveWrites) {
  const auto dir = freshTempDir("TrackerParams_fuzzSeed");
  TrackerParams{}.save(dir / "defaults.yml");
  EXPECT_EQ(readTextFile(sourceDir() / "tests/fuzz/corpus/params_file/tracker_defaults.yml"),
            readTextFile(dir / "defaults.yml"))
      << "refresh the seed: copy " << (dir / "defaults.yml").string();
}
