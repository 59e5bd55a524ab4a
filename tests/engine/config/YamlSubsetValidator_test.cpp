// YamlSubsetValidator: the YAML subset reftrack writes is accepted (every writer's output, the
// shared recordings' files, the fuzz seeds); everything else is refused naming line and reason.
#include "engine/config/YamlSubsetValidator.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "TestPaths.hpp"
#include "engine/config/MapExtensionParams.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/estimation/MotionModelFile.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/homography/AnnotationSet.hpp"
#include "engine/reference/MultiReferenceMap.hpp"
#include "engine/reference/ReferenceMap.hpp"
#include "engine/reference/ReferencePreparer.hpp"

using namespace reftrack;

namespace {

std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// "line N: reason", or "ok".
std::string verdict(const std::string& text) {
  const auto v = findYamlSubsetViolation(text);
  return v ? "line " + std::to_string(v->line) + ": " + v->reason : "ok";
}

std::string memoryYaml(const std::function<void(cv::FileStorage&)>& write) {
  cv::FileStorage fs(
      ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  write(fs);
  return fs.releaseAndGetString();
}

}  // namespace

TEST(YamlSubsetValidator, AcceptsTheSubsetReftrackFilesUse) {
  for (const std::string text : {
           "",
           "# only a comment\n",
           "%YAML:1.0\n",
           "%YAML:1.0\n---\n",
           "%YAML 1.2 # a comment\na: 1\n",
           "\xEF\xBB\xBF"
           "a: 1\r\nb: 2\r\n",
           "a: 1",  // no final line break
           "a: -1\nb: +2.5e-3\nc: .5\nd: 0x1F\ne: 1.\nf: [ .Nan, -.Inf, .Inf ]\n",
           "mode: homography\npath: /data/my clip (2).mp4\nname: \"6dof\"\nq: 'it''s'\n",
           "text: \"%YAML:1.0\\n50% off: \\\"yes\\\" \\\\ \\t\"\n",
           "ransac:\n  max_iterations: 200\n\n  # a comment line\n  seed: 3\nnext: 1\n",
           "pose: {estimator: standard, alpha: 2.5}\nempty_map: {}\nempty_list: []\n",
           "labels:\n  - { text: \"Tower\", x: 120, y: 80 }\n  - {text: \"Bridge: east\", x: 1, y: "
           "2}\n",
           "labels:\n   -\n      text: Lamp\n      x: 150.\n   - text: Post\n     x: 1\n",
           "K: !!opencv-matrix\n   rows: 1\n   cols: 2\n   dt: d\n   data: [ 1., 2. ]\n",
           "K: !!opencv-matrix { rows: 1, cols: 1, dt: d, data: [ 1 ] }\n",
           "data: [ 1, 2,\n    3, 4 ]\nnested: [[1, 2], [3]]\n",
           "a:\n   5\nb:\n   - - 1\n     - 2\n",
           "a: 5 # five\nb: [1] # a list\nc: \"x\" # text\nd: C# and F#\n",
       })
    EXPECT_EQ(verdict(text), "ok") << text;
}

TEST(YamlSubsetValidator, RefusesEverythingElseNamingTheLineAndWhatIsWrong) {
  const std::pair<std::string, std::string> cases[] = {
      // Structure: one map at column 1, nothing after it.
      {"- 1\n- 2\n", "line 1: the top level must be a map of 'key: value' lines, not a list"},
      {"  a: 1\n",
       "line 1: the top-level keys must start at the beginning of the line (no "
       "indentation)"},
      {"{a: 1}\n",
       "line 1: a top-level { } map (or JSON) is not supported: write 'key: value' "
       "lines starting at column 1"},
      {"a: 1\n---\nb: 2\n",
       "line 2: a second document ('---') is not supported: a file holds "
       "one map"},
      {"---x\na: 1\n", "line 1: '---' must stand alone on its line"},
      {"a: 1\n...\n", "line 2: '...' (end of document) is not supported"},
      {"%YAML:1.0\n%YAML:1.0\na: 1\n", "line 2: a '%' directive is allowed only as the first line"},
      {"%TAG ! x\na: 1\n",
       "line 1: the first line may only be the directive %YAML:1.0 (or leave "
       "it out)"},
      {"<?xml version=\"1.0\"?>\n",
       "line 1: this looks like XML; reftrack reads YAML only ('key: "
       "value' lines)"},
      {"a: {\"b\": 1}\n", "line 1: keys are written without quotes"},
      // Characters.
      {"a:\n\tb: 1\n", "line 2: a tab character: YAML indents with spaces only"},
      {"a: 1\rb: 2\n", "line 1: a carriage return inside the line"},
      {std::string("a: 1\nb: \0\n", 10), "line 2: a NUL byte (is this a binary file?)"},
      {"a: \x01\n", "line 1: a control character (byte 0x01)"},
      // Keys and indentation.
      {"ransac:\nmax_iterations: 1\n", "line 1: 'ransac:' has no value"},
      {"labels:\n- 1\n",
       "line 1: the '- ' items under 'labels:' must be indented more than the "
       "key"},
      {"a:\n  b: 1\n   c: 2\n",
       "line 3: unexpected indentation: expected 2 spaces, like the key "
       "on line 2"},
      {"a: 1\na: 2\n", "line 2: the key 'a' appears twice in the same map (first on line 1)"},
      {"p: {x: 1, x: 2}\n", "line 1: the key 'x' appears twice in the same map (first on line 1)"},
      {"a b\n", "line 1: expected 'key: value' (no ':' on this line)"},
      {"a.b: 1\n", "line 1: a key may hold only letters, digits, '_', '-' and spaces, not '.'"},
      {"1a: 1\n", "line 1: a key must start with a letter or '_', not '1'"},
      // Values.
      {"a: b: c\n",
       "line 1: text containing ':' must be quoted (\"...\"); a nested map goes on "
       "the following, indented lines"},
      {"mode: homography # the fast one\n",
       "line 1: a comment after text is read by OpenCV as part of the text: move the comment to "
       "its own line or quote the text"},
      {"mode: 6dof\n",
       "line 1: '6dof' is not a number; quote text that starts like one "
       "(\"6dof\")"},
      {"seed: 99999999999\n",
       "line 1: '99999999999' is too large for a whole number (OpenCV's "
       "are 32-bit); quote it if it is text"},
      {"a: - 1\n", "line 1: a '- ' list must start on the line after 'key:', one item per line"},
      {"a:\n  -1x\n",
       "line 2: '-1x' is not a number; quote text that starts like one "
       "(\"-1x\")"},
      {"a:\n  -x\n", "line 2: a list item needs a space after '-'"},
      {"a:\n  - 1\n  b: 2\n", "line 3: expected another '- ' list item, or less indentation"},
      {"a: \"open\n", "line 1: a quoted text must end on the line where it starts (missing \")"},
      {"a: \"\\x41\"\n",
       "line 1: unsupported escape '\\x' in a quoted text (use \\n, \\t, \\\\ "
       "or \\\")"},
      {"a: [1, 2\nb: 3\n", "line 2: a continued [ ] must be indented by at least 2 spaces"},
      {"a: [1, 2\n", "line 1: '[' is never closed with ']'"},
      {"a: [1, 2}\n", "line 1: '}' where ']' should close the '[' of line 1"},
      {"a: [1 2]\n", "line 1: expected ',' or ']'"},
      {"a: [1, ]\n", "line 1: a ',' must be followed by another element"},
      {"a: [x[1]]\n", "line 1: text containing '[' inside [ ] or { } must be quoted"},
      {"a: !!binary |\n",
       "line 1: unsupported type tag '!!binary' (only !!opencv-matrix and "
       "!!opencv-nd-matrix)"},
      {"a: !!opencv-matrix\nb: 1\n",
       "line 1: !!opencv-matrix must be followed by its fields "
       "(rows, cols, dt, data) as a map on the following, indented "
       "lines"},
      {"a: &x 1\n", "line 1: anchors and aliases ('&', '*') are not supported"},
      {"a: |\n  text\n",
       "line 1: multi-line text ('|' or '>') is not supported; write it as one "
       "quoted line"},
      {"? a\n", "line 1: a key must start with a letter or '_', not '?'"},
      {"a: @x\n", "line 1: text starting with '@' must be quoted (\"...\")"},
  };
  for (const auto& [text, expected] : cases) EXPECT_EQ(verdict(text), expected) << text;
  // Nesting is bounded (OpenCV's parser recurses once per level).
  EXPECT_EQ(verdict("a: " + std::string(40, '[') + std::string(40, ']') + "\n"),
            "line 1: values nested deeper than 16 levels");
  // A quoted text longer than OpenCV's buffer.
  EXPECT_EQ(verdict("a: \"" + std::string(5000, 'x') + "\"\n"),
            "line 1: a quoted text longer than 4095 characters");
}

// Each writer of a YAML file reftrack reads back: its output keeps to the subset (a file that
// did not would be refused by its own reader).
TEST(YamlSubsetValidator, EveryWritersOutputKeepsToTheSubset) {
  const auto dir = test::freshTempDir("YamlSubsetValidator_writers");
  const PinholeCamera camera(
      (Eigen::Matrix3d() << 150.0, 0, 79.5, 0, 151.0, 59.5, 0, 0, 1).finished(), {160, 120},
      {0.01, -0.002, 0.0005, 0.0001, 0.0});
  camera.save(dir / "camera.yml");

  const AnnotationSet labels(
      {{"Tower: \"north\" 100%", cv::Point2d(120.5, 80)}, {"#2", cv::Point2d(1, 2)}});
  labels.save(dir / "labels.yml");

  FittedMotionModel motion;
  Vector6d w;
  w << 1.5, 1.2, 0.9, 1.4, 1.1, 1.3;
  motion.model = ArMotionModel({w}, ArMotionModel::diagonalNoise(0.002, 0.003));
  motion.explainedVariance << 0.9, 0.8, 0.7, 0.85, 0.84, 0.6;
  motion.sourceTrajectory = "my trajectory: take 2.txt";
  motion.frameCount = 321;
  saveMotionModel(dir / "motion.yml", motion);

  TrackerParams{}.save(dir / "params.yml");

  ReferenceMap pair;
  pair.camera = camera;
  pair.T_A = RigidPose::fromVector6((Vector6d() << 0, 0, 1, 0.1, 0, 0).finished());
  pair.T_B = RigidPose::fromVector6((Vector6d() << -0.2, 0, 1, 0.1, -0.2, 0).finished());
  pair.imageA = cv::Mat(120, 160, CV_8UC3, cv::Scalar(10, 20, 30));
  pair.imageB = pair.imageA.clone();
  pair.cornersA = {{{10.5f, 20.25f}, 30.f}};
  pair.cornersB = {{{12.f, 21.f}, 28.f}};
  pair.matches = {{0, 0, Eigen::Vector3d(0.1, -0.05, 1.2)}};
  pair.poseSource = "test";
  pair.save(dir / "pair");

  MultiReferenceMap map;
  map.camera = camera;
  for (int v = 0; v < 2; ++v) {
    ReferenceView view;
    view.name = "reference_0" + std::to_string(v) + ".png";
    view.T = RigidPose::fromVector6((Vector6d() << 0.1 * v, 0, 1, 0.1, 0, 0).finished());
    view.anchored = true;
    view.image = pair.imageA;
    view.corners = {{{10.5f + v, 20.25f}, 30.f}, {{100.f, 60.f}, 12.5f}};
    map.views.push_back(view);
  }
  ReferenceKeypoints& kp = map.views[1].keypoints;
  kp.keypoints = {cv::KeyPoint(12.5f, 30.25f, 31.f, 45.5f, 0.003f, 2)};
  kp.descriptors = cv::Mat(1, 32, CV_8U, cv::Scalar(7));
  kp.points = {Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN())};
  map.points = {{Eigen::Vector3d(0.1, -0.05, 0.2), {{0, 0}, {1, 0}}}};
  map.keypointKind = "orb";
  map.poseSource = "marker";
  // The preparation parameters are stored as one quoted YAML text with line breaks and '%'.
  map.preparationParams =
      memoryYaml([](cv::FileStorage& fs) { ReferencePreparerParams{}.write(fs); });
  map.save(dir / "map");

  const std::pair<std::string, std::string> written[] = {
      {"camera.yml", readText(dir / "camera.yml")},
      {"labels.yml", readText(dir / "labels.yml")},
      {"motion.yml", readText(dir / "motion.yml")},
      {"params.yml", readText(dir / "params.yml")},
      {"pair/map.yml", readText(dir / "pair" / "map.yml")},
      {"map/map.yml", readText(dir / "map" / "map.yml")},
      {"preparation parameters", map.preparationParams},
      {"extension parameters",
       memoryYaml([](cv::FileStorage& fs) { MapExtensionParams{}.write(fs); })},
  };
  for (const auto& [name, text] : written) {
    ASSERT_FALSE(text.empty()) << name;
    EXPECT_EQ(verdict(text), "ok") << name << ":\n" << text;
  }
  // And each loads back through its reader (which applies the validator).
  EXPECT_EQ(PinholeCamera::load(dir / "camera.yml").K(), camera.K());
  EXPECT_EQ(AnnotationSet::load(dir / "labels.yml").labels().size(), 2u);
  EXPECT_EQ(loadMotionModel(dir / "motion.yml").frameCount, 321);
  EXPECT_NO_THROW(TrackerParams::load(dir / "params.yml"));
  EXPECT_NO_THROW(ReferenceMap::load(dir / "pair"));
  EXPECT_EQ(MultiReferenceMap::load(dir / "map").preparationParams, map.preparationParams);
}

// The YAML files of the shared recordings and the fuzz seed corpora keep to the subset.
TEST(YamlSubsetValidator, SharedRecordingsAndFuzzSeedsKeepToTheSubset) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(test::sourceDir() / "tests" /
                                                                     "fuzz" / "corpus"))
    if (e.path().extension() == ".yml") files.push_back(e.path());
  const std::size_t seeds = files.size();
  EXPECT_GE(seeds, 15u);
  if (const auto shared = test::sharedDataDir()) {
    for (const auto& e : std::filesystem::recursive_directory_iterator(*shared))
      if (e.path().extension() == ".yml" || e.path().extension() == ".yaml")
        files.push_back(e.path());
  } else {
    std::cout << "[ note ] ../shared/data absent: only the fuzz seeds are checked\n";
  }
  for (const auto& file : files) EXPECT_EQ(verdict(readText(file)), "ok") << file;
}
