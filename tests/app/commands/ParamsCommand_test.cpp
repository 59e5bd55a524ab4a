#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "app/commands/CommandTestSupport.hpp"
#include "app/viewer/ViewerSettings.hpp"
#include "engine/config/ConfigFile.hpp"
#include "engine/config/FieldDescriber.hpp"
#include "engine/config/TrackerParams.hpp"

using namespace reftrack;

namespace {

std::string savedYaml(const TrackerParams& p) {
  cv::FileStorage fs(
      ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  p.write(fs);
  return fs.releaseAndGetString();
}

std::string savedYaml(const app::OverlaySettings& o) {
  cv::FileStorage fs(
      ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  FieldWriter{fs}(o);
  return fs.releaseAndGetString();
}

void collectKeys(const YamlNode& map, const std::string& prefix, std::vector<std::string>& out) {
  for (const YamlNode& child : map.children()) {
    const std::string key = prefix.empty() ? child.key() : prefix + "." + child.key();
    if (child.isMap())
      collectKeys(child, key, out);
    else
      out.push_back(key);
  }
}

// The keys the viewer's parameter file holds: TrackerParams::save()'s and the overlay section's.
std::vector<std::string> savedKeys() {
  std::vector<std::string> keys;
  collectKeys(readConfigText(savedYaml(TrackerParams{}), "saved"), "", keys);
  collectKeys(readConfigText(savedYaml(app::OverlaySettings{}), "overlay"), "", keys);
  return keys;
}

// The listing's row of `key`: "  <key>  <default>  <allowed>  <meaning>", or "".
std::string rowOf(const std::string& listing, const std::string& key) {
  std::istringstream lines(listing);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("  " + key + " ", 0) == 0) return line;
  return "";
}

}  // namespace

TEST(ParamsCommand, ListsEverySavedKeyWithItsDefaultRuleAndMeaning) {
  const auto dir = test::freshTempDir("ParamsCommand_list");
  const auto r = test::runReftrack("params", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::vector<ParamDescription> described = describeParams(TrackerParams{});
  for (const ParamDescription& d : describeParams(app::OverlaySettings{})) described.push_back(d);
  const std::vector<std::string> keys = savedKeys();
  ASSERT_GT(keys.size(), 100u);
  for (const std::string& key : keys) {
    const std::string row = rowOf(r.out, key);
    ASSERT_FALSE(row.empty()) << key << " is not listed";
    const auto d = std::find_if(described.begin(), described.end(),
                                [&](const ParamDescription& p) { return p.key == key; });
    ASSERT_NE(d, described.end()) << key;
    EXPECT_FALSE(d->help.empty()) << key << " has no meaning";
    EXPECT_NE(row.find(" " + d->value + " "), std::string::npos) << row;
    EXPECT_NE(row.find(" " + d->allowed + " "), std::string::npos) << row;
    EXPECT_EQ(row.substr(row.size() - d->help.size()), d->help) << row;
  }
  EXPECT_NE(rowOf(r.out, "corners.count").find("[4, 100000]"), std::string::npos);
  EXPECT_NE(rowOf(r.out, "mode").find("6dof | homography"), std::string::npos);
  EXPECT_NE(r.out.find("\ncorners:\n"), std::string::npos);
}

TEST(ParamsCommand, ListsOnlyTheKeysAndSectionsAsked) {
  const auto dir = test::freshTempDir("ParamsCommand_filter");
  const auto r = test::runReftrack("params corners pose.alpha", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_FALSE(rowOf(r.out, "corners.count").empty());
  EXPECT_FALSE(rowOf(r.out, "corners.contrast_window").empty());
  EXPECT_FALSE(rowOf(r.out, "pose.alpha").empty());
  EXPECT_TRUE(rowOf(r.out, "pose.ar_order").empty());
  EXPECT_TRUE(rowOf(r.out, "mode").empty());

  const auto byName = test::runReftrack("params min_inliers", dir);
  ASSERT_EQ(byName.exitCode, 0) << byName.err;
  EXPECT_FALSE(rowOf(byName.out, "ransac.min_inliers").empty());
  EXPECT_FALSE(rowOf(byName.out, "relocalisation.min_inliers").empty());

  const auto unknown = test::runReftrack("params ransac.max_iteration", dir);
  EXPECT_EQ(unknown.exitCode, 2);
  EXPECT_NE(unknown.err.find("did you mean 'ransac.max_iterations'"), std::string::npos)
      << unknown.err;
}

TEST(ParamsCommand, WritesTheDefaultsAsACommentedFileParamsAccepts) {
  const auto dir = test::freshTempDir("ParamsCommand_write");
  const auto file = dir / "params.yml";
  const auto r = test::runReftrack("params --write " + file.string(), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("wrote " + file.string()), std::string::npos) << r.out;
  // `--params` of every command reads it with TrackerParams::load, the viewer with its overlay.
  EXPECT_EQ(savedYaml(TrackerParams::load(file)), savedYaml(TrackerParams{}));
  const app::ViewerSettings viewer = app::ViewerSettings::load(file);
  EXPECT_EQ(savedYaml(viewer.overlay), savedYaml(app::OverlaySettings{}));

  // Every key is preceded by its comment: its meaning and the values allowed.
  const std::string text = test::readTextFile(file);
  EXPECT_NE(text.find("corners:\n  # Corners detected per image at 320x240"), std::string::npos);
  EXPECT_NE(text.find(" ([4, 100000])\n  count: 55\n"), std::string::npos) << text;
  EXPECT_NE(text.find(" (6dof | homography)\nmode: \"6dof\"\n"), std::string::npos) << text;

  // A section alone: a file with only those keys, which loads too.
  const auto pose = test::runReftrack("params pose --write " + (dir / "pose.yml").string(), dir);
  ASSERT_EQ(pose.exitCode, 0) << pose.err;
  const std::string poseText = test::readTextFile(dir / "pose.yml");
  EXPECT_NE(poseText.find("pose:\n"), std::string::npos);
  EXPECT_EQ(poseText.find("corners:"), std::string::npos);
  EXPECT_EQ(savedYaml(TrackerParams::load(dir / "pose.yml")), savedYaml(TrackerParams{}));
}

// The section `prepare --unprepared --params` reads is listed (and written) when asked for, never
// with the tracking parameters, and not mixed with them in one file.
TEST(ParamsCommand, TheUnpreparedSectionIsListedAndWrittenOnItsOwn) {
  const auto dir = test::freshTempDir("ParamsCommand_unprepared");
  const auto all = test::runReftrack("params", dir);
  ASSERT_EQ(all.exitCode, 0) << all.err;
  EXPECT_TRUE(rowOf(all.out, "unprepared.min_parallax_deg").empty());
  EXPECT_NE(all.out.find("`reftrack params unprepared`"), std::string::npos);
  const auto listed = test::runReftrack("params unprepared", dir);
  ASSERT_EQ(listed.exitCode, 0) << listed.err;
  EXPECT_FALSE(rowOf(listed.out, "unprepared.min_parallax_deg").empty());
  EXPECT_FALSE(rowOf(listed.out, "unprepared.max_rotation_share").empty());
  EXPECT_NE(listed.out.find("`prepare --unprepared --params`"), std::string::npos) << listed.out;
  const auto file = dir / "unprepared.yml";
  const auto written = test::runReftrack("params unprepared --write " + file.string(), dir);
  ASSERT_EQ(written.exitCode, 0) << written.err;
  const std::string text = test::readTextFile(file);
  EXPECT_NE(text.find("unprepared:\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("corners:"), std::string::npos);
  const auto mixed =
      test::runReftrack("params unprepared ransac --write " + (dir / "mixed.yml").string(), dir);
  EXPECT_EQ(mixed.exitCode, 2);
  EXPECT_NE(mixed.err.find("write them to two files"), std::string::npos) << mixed.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "mixed.yml"));
}

TEST(ParamsCommand, AFileItCannotWriteIsAClearErrorAndLeavesNothing) {
  const auto dir = test::freshTempDir("ParamsCommand_unwritable");
  const auto missing = dir / "no-such-folder" / "params.yml";
  const auto r = test::runReftrack("params --write " + missing.string(), dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("cannot write parameter file '" + missing.string() + "'"), std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "no-such-folder"));

  std::filesystem::create_directory(dir / "folder");
  const auto folder = test::runReftrack("params --write " + (dir / "folder").string(), dir);
  EXPECT_EQ(folder.exitCode, 1);
  EXPECT_NE(folder.err.find("it is a folder"), std::string::npos) << folder.err;
  EXPECT_TRUE(std::filesystem::is_empty(dir / "folder"));
}
