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

TEST(KnownKeys, UnknownKeyNamesItAndTheNearestKnownKey) {
  const cv::FileStorage fs = parseYaml("ransac:\n  iterations: 200\n");
  EXPECT_EQ(errorMessage([&] {
              requireKnownKeys(fs["ransac"], "ransac", {"max_iterations", "seed"});
            }),
            "ransac.iterations: unknown key — did you mean ransac.max_iterations?");
  EXPECT_EQ(errorMessage([&] { requireKnownKeys(fs["ransac"], "ransac", {}); }),
            "ransac.iterations: unknown key — this map takes no keys");
  EXPECT_EQ(errorMessage([&] { requireKnownKeys(fs["ransac"], "ransac", {"iterations"}); }),
            "(no error)");
}

TEST(KnownKeys, AMapIsASectionButAnOpenCvMatrixIsAKey) {
  const cv::FileStorage fs = parseYaml(
      "ransca:\n  seed: 1\ncamera_matrx: !!opencv-matrix\n  rows: 1\n  cols: 1\n  dt: d\n"
      "  data: [1.]\n");
  EXPECT_EQ(errorMessage([&] {
              requireKnownKeys(fs.root(), "", {"ransac", "camera_matrx"});
            }),
            "ransca: unknown section — did you mean ransac?");
  EXPECT_EQ(errorMessage([&] {
              requireKnownKeys(fs.root(), "", {"ransca", "camera_matrix"});
            }),
            "camera_matrx: unknown key — did you mean camera_matrix?");
}

TEST(KnownKeys, AbsentOrNonMapNodesAreLeftToTheReader) {
  const cv::FileStorage fs = parseYaml("list: [1, 2]\nvalue: 3\n");
  EXPECT_EQ(errorMessage([&] { requireKnownKeys(fs["missing"], "missing", {}); }), "(no error)");
  EXPECT_EQ(errorMessage([&] { requireKnownKeys(fs["list"], "list", {}); }), "(no error)");
  EXPECT_EQ(errorMessage([&] { requireKnownKeys(fs["value"], "value", {}); }), "(no error)");
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
  const cv::FileStorage good = parseYaml("mode: y\nransac:\n  max_iterations: 5\n  seed: 2\n");
  EXPECT_EQ(errorMessage([&] { requireKeysWrittenBy(good.root(), "", writer); }), "(no error)");
  const cv::FileStorage key = parseYaml("ransac:\n  iterations: 5\n");
  EXPECT_EQ(errorMessage([&] { requireKeysWrittenBy(key.root(), "", writer); }),
            "ransac.iterations: unknown key — did you mean ransac.max_iterations?");
  const cv::FileStorage section = parseYaml("ransak:\n  max_iterations: 5\n");
  EXPECT_EQ(errorMessage([&] { requireKeysWrittenBy(section.root(), "", writer); }),
            "ransak: unknown section — did you mean ransac?");
  // Sections another reader of the same file handles are accepted, with any content.
  const cv::FileStorage other = parseYaml("overlay:\n  size: 2\n");
  EXPECT_EQ(errorMessage([&] { requireKeysWrittenBy(other.root(), "", writer, {"overlay"}); }),
            "(no error)");
}
