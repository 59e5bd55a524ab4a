// KnownKeys: an unknown key or section names itself and the nearest known key.
#include "engine/config/KnownKeys.hpp"

#include <gtest/gtest.h>

#include "engine/config/ParamsTestSupport.hpp"
#include "engine/config/RansacParams.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(KnownKeys, EditDistanceCountsSingleByteEdits) {
  EXPECT_EQ(editDistance("", ""), 0u);
  EXPECT_EQ(editDistance("abc", ""), 3u);
  EXPECT_EQ(editDistance("", "ab"), 2u);
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);  // the textbook example
  EXPECT_EQ(editDistance("ransac", "ransca"), 2u);   // a swap is two substitutions
  EXPECT_EQ(editDistance("iterations", "max_iterations"), 4u);
  EXPECT_EQ(editDistance("same", "same"), 0u);
}

TEST(KnownKeys, NearestKeyPrefersTheSmallestDistanceThenTheFirst) {
  EXPECT_EQ(nearestKey("iterations", {"seed", "max_iterations", "min_inliers"}), "max_iterations");
  EXPECT_EQ(nearestKey("ab", {"ax", "xb"}), "ax");
  // Fewer edits reach "order" (5) than "source_trajectory" (10), but the shared prefix wins.
  EXPECT_EQ(editDistance("source_x", "order"), 5u);
  EXPECT_EQ(nearestKey("source_x", {"kind", "order", "source_trajectory"}), "source_trajectory");
  EXPECT_EQ(nearestKey("frames_count", {"frame_count", "count"}), "frame_count");
  EXPECT_EQ(nearestKey("anything", {}), "");
}

TEST(KnownKeys, UnknownKeyNamesItsLineItAndTheNearestKnownKey) {
  const YamlNode root = parseYaml("# ransac\nransac:\n  iterations: 200\n");
  EXPECT_EQ(errorMessage([&] {
              requireKnownKeys(root["ransac"], {"max_iterations", "seed"});
            }),
            "line 3: ransac.iterations: unknown key — did you mean ransac.max_iterations?");
  EXPECT_EQ(errorMessage([&] { requireKnownKeys(root["ransac"], {}); }),
            "line 3: ransac.iterations: unknown key — this map takes no keys");
  EXPECT_EQ(errorMessage([&] { requireKnownKeys(root["ransac"], {"iterations"}); }), "(no error)");
}

// The example: a flow map on line 3 with a misspelt key.
TEST(KnownKeys, AMisspeltKeyInAFlowMapNamesItsLine) {
  const YamlNode root =
      parseYaml("mode: 6dof\n# tuned for the desk\nransac: {max_iteratons: 80}\n");
  EXPECT_EQ(errorMessage([&] {
              requireKeysWrittenBy(root, [](cv::FileStorage& out) {
                out << "mode"
                    << "6dof"
                    << "ransac"
                    << "{";
                RansacParams{}.write(out);
                out << "}";
              });
            }),
            "line 3: ransac.max_iteratons: unknown key — did you mean ransac.max_iterations?");
}

TEST(KnownKeys, AMapIsASectionButAnOpenCvMatrixIsAKey) {
  const YamlNode root = parseYaml(
      "ransca:\n  seed: 1\ncamera_matrx: !!opencv-matrix\n  rows: 1\n  cols: 1\n  dt: d\n"
      "  data: [1.]\n");
  EXPECT_EQ(errorMessage([&] {
              requireKnownKeys(root, {"ransac", "camera_matrx"});
            }),
            "line 1: ransca: unknown section — did you mean ransac?");
  EXPECT_EQ(errorMessage([&] {
              requireKnownKeys(root, {"ransca", "camera_matrix"});
            }),
            "line 3: camera_matrx: unknown key — did you mean camera_matrix?");
}

TEST(KnownKeys, AYaml11MergeKeyIsExplained) {
  const YamlNode root = parseYaml("base: &b {seed: 1}\nransac:\n  <<: *b\n");
  EXPECT_EQ(
      errorMessage([&] { requireKnownKeys(root["ransac"], {"seed"}); }),
      "line 3: ransac.<<: unknown section — '<<' merges maps in YAML 1.1 only; write the keys out "
      "(an alias may stand for a whole section)");
}

TEST(KnownKeys, AbsentOrNonMapNodesAreLeftToTheReader) {
  const YamlNode root = parseYaml("list: [1, 2]\nvalue: 3\nempty:\n");
  for (const char* key : {"missing", "list", "value", "empty"})
    EXPECT_EQ(errorMessage([&] { requireKnownKeys(root[key], {}); }), "(no error)") << key;
}

TEST(KnownKeys, KeysWrittenByTheWriterAreKnownIntoNestedSections) {
  const auto writer = [](cv::FileStorage& out) {
    out << "mode"
        << "x"
        << "ransac"
        << "{";
    RansacParams{}.write(out);
    out << "}";
  };
  const YamlNode good = parseYaml("mode: y\nransac:\n  max_iterations: 5\n  seed: 2\n");
  EXPECT_EQ(errorMessage([&] { requireKeysWrittenBy(good, writer); }), "(no error)");
  const YamlNode key = parseYaml("ransac:\n  iterations: 5\n");
  EXPECT_EQ(errorMessage([&] { requireKeysWrittenBy(key, writer); }),
            "line 2: ransac.iterations: unknown key — did you mean ransac.max_iterations?");
  const YamlNode section = parseYaml("ransak:\n  max_iterations: 5\n");
  EXPECT_EQ(errorMessage([&] { requireKeysWrittenBy(section, writer); }),
            "line 1: ransak: unknown section — did you mean ransac?");
  // Sections another reader of the same file handles are accepted, with any content.
  const YamlNode other = parseYaml("overlay:\n  size: 2\n");
  EXPECT_EQ(errorMessage([&] { requireKeysWrittenBy(other, writer, {"overlay"}); }), "(no error)");
}
