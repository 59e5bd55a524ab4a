#include "engine/config/CommentedParamsFile.hpp"

#include <gtest/gtest.h>

#include "TestPaths.hpp"
#include "engine/config/ParamsTestSupport.hpp"
#include "engine/config/TrackerParams.hpp"

using namespace reftrack;
using namespace reftrack::test;

namespace {

std::string savedYaml(const TrackerParams& p) {
  cv::FileStorage fs(
      ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  p.write(fs);
  return fs.releaseAndGetString();
}

}  // namespace

TEST(CommentedParamsFile, NestsSectionsAndPutsEachKeysMeaningAndRuleAboveIt) {
  const std::vector<ParamDescription> keys = {
      {"mode", "\"6dof\"", "6dof | homography", "the mode"},
      {"a.x", "1", "[0, 9]", "x of a"},
      {"a.b.y", "2.0", "", "y"},
      {"a.z", "true", "true | false", ""},
      {"c.w", "3", "[1, 3]", "w"},
  };
  EXPECT_EQ(commentedParamsYaml(keys, "Title\n\nmore"),
            "# Title\n#\n# more\n"
            "\n# the mode (6dof | homography)\nmode: \"6dof\"\n"
            "\na:\n  # x of a ([0, 9])\n  x: 1\n"
            "  b:\n    # y\n    y: 2.0\n"
            "  # (true | false)\n  z: true\n"
            "\nc:\n  # w ([1, 3])\n  w: 3\n");
}

TEST(CommentedParamsFile, TheDefaultsFileReadsBackToTheDefaults) {
  const std::string yaml = commentedParamsYaml(describeParams(TrackerParams{}), "defaults");
  EXPECT_EQ(savedYaml(TrackerParams::parse(yaml, "defaults")), savedYaml(TrackerParams{}));
}

TEST(CommentedParamsFile, AnyValuesReadBackExactly) {
  TrackerParams p;
  p.mode = TrackingMode::Homography;
  p.corners.quality = 0.1 + 0.2;
  p.correlation.minScore = -0.25;
  p.homography.keypoints = KeypointLayer::None;
  p.homography.reacquireCornerQuality = 3.3e-6;
  p.pose.estimator = PoseEstimatorKind::Standard;
  p.pose.motionModelFile = "my \"motion\" \\ file.yml";
  p.pose.translationSigma = 123456.789;
  p.relocalisation.enabled = false;
  p.relocalisation.keypoints = "orb";
  p.ransac.seed = 2147483647;
  const std::string yaml = commentedParamsYaml(describeParams(p), "");
  const TrackerParams back = TrackerParams::parse(yaml, "edited");
  EXPECT_EQ(savedYaml(back), savedYaml(p));
  EXPECT_EQ(back.pose.motionModelFile, p.pose.motionModelFile);
  EXPECT_EQ(back.corners.quality, p.corners.quality);
}

TEST(CommentedParamsFile, WritesTheFileOrFailsLeavingNothing) {
  const auto dir = freshTempDir("CommentedParamsFile_write");
  const std::vector<ParamDescription> keys = describeParams(TrackerParams{});
  writeCommentedParamsFile(dir / "params.yml", keys, "defaults");
  EXPECT_EQ(readTextFile(dir / "params.yml"), commentedParamsYaml(keys, "defaults"));
  EXPECT_EQ(savedYaml(TrackerParams::load(dir / "params.yml")), savedYaml(TrackerParams{}));

  const std::string missing =
      errorMessage([&] { writeCommentedParamsFile(dir / "no" / "params.yml", keys, ""); });
  EXPECT_NE(missing.find("cannot write parameter file '" + (dir / "no" / "params.yml").string() +
                         "': output folder"),
            std::string::npos)
      << missing;
  std::filesystem::create_directory(dir / "folder");
  const std::string folder =
      errorMessage([&] { writeCommentedParamsFile(dir / "folder", keys, ""); });
  EXPECT_NE(folder.find("it is a folder"), std::string::npos) << folder;
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    (void)entry;
    ++files;
  }
  EXPECT_EQ(files, 2u);  // params.yml and the folder: no temporary file left
}
