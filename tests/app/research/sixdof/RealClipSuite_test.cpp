#include "app/research/sixdof/RealClipSuite.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"

namespace reftrack::app {
namespace {

using test::errorMessage;

// The project's suite file names every real clip with true poses, with the placements, ranges
// and thresholds its comments give.
TEST(RealClipSuite, TheProjectsSuiteNamesEveryRealClip) {
  const RealClipSuite suite =
      loadRealClipSuite(test::sourceDir() / "app" / "research" / "suites" / "real-clips.yml");
  std::vector<std::string> names;
  for (const RealClip& clip : suite.clips) names.push_back(clip.name);
  EXPECT_EQ(names, (std::vector<std::string>{"desk-chessboard", "shelf-apriltags",
                                             "visp-desk-apriltags", "kinect-kitchen-0-70",
                                             "kinect-kitchen-180-300", "kinect-kitchen-280-400"}));
  const RealClip& desk = suite.clips[0];
  EXPECT_EQ(desk.folder, "desk-chessboard");
  EXPECT_EQ(desk.frames, "frames");
  EXPECT_EQ(desk.camera, "camera.yml");
  EXPECT_EQ(desk.groundTruth, "groundtruth.txt");
  EXPECT_EQ(desk.references, (std::vector<int>{0, 40}));
  EXPECT_EQ(desk.firstFrame, 0);
  EXPECT_FALSE(desk.lastFrame);
  EXPECT_EQ(desk.frameCount(), 0);
  EXPECT_DOUBLE_EQ(desk.cubeEdge, 0.1);
  EXPECT_EQ(desk.cubeBaseCentre, Eigen::Vector3d(0.16, -0.10, 0));
  EXPECT_EQ(desk.cubeInFrontM, 0.0);
  EXPECT_DOUBLE_EQ(desk.wrongPx, 5.0);
  const RealClip& shelf = suite.clips[1];
  EXPECT_EQ(shelf.references, (std::vector<int>{0, 60}));
  EXPECT_EQ(shelf.cubeBaseCentre, Eigen::Vector3d(0.1, 0.2, -0.12));
  EXPECT_DOUBLE_EQ(shelf.cubeEdge, 0.05);
  const RealClip& visp = suite.clips[2];
  EXPECT_EQ(visp.cubeBaseCentre, Eigen::Vector3d(0.18, 0.12, 0));
  for (const auto& [index, first, last, a, b] :
       {std::tuple{3, 0, 70, 0, 40}, std::tuple{4, 180, 300, 200, 220},
        std::tuple{5, 280, 400, 300, 320}}) {
    const RealClip& kinect = suite.clips[static_cast<std::size_t>(index)];
    EXPECT_EQ(kinect.folder, "kinect-kitchen");
    EXPECT_EQ(kinect.firstFrame, first);
    ASSERT_TRUE(kinect.lastFrame);
    EXPECT_EQ(*kinect.lastFrame, last);
    EXPECT_EQ(kinect.frameCount(), last - first + 1);
    EXPECT_EQ(kinect.references, (std::vector<int>{a, b}));
    EXPECT_DOUBLE_EQ(kinect.cubeEdge, 0.08);
    EXPECT_DOUBLE_EQ(kinect.cubeInFrontM, 1.0);
    EXPECT_DOUBLE_EQ(kinect.wrongPx, 20.0);
  }
  EXPECT_EQ(suite.find("kinect-kitchen-0-70"), &suite.clips[3]);
  EXPECT_EQ(suite.find("kinect"), nullptr);
}

// The text of a one-clip suite with `clip` (YAML lines, indented under "- ") as its clip.
std::string oneClip(const std::string& clip) { return "clips:\n  - " + clip; }

const std::string kGood =
    "name: a\n    folder: a\n    references: [0, 4]\n    cube: {edge: 0.1, base_centre: [0, 0, "
    "0]}\n"
    "    wrong_px: 5\n";

TEST(RealClipSuite, AValidSuiteParses) {
  const RealClipSuite suite = parseRealClipSuite(oneClip(kGood), "suite S");
  ASSERT_EQ(suite.clips.size(), 1u);
  EXPECT_EQ(suite.clips[0].line, 2);
  EXPECT_EQ(suite.description, "suite S");
}

// A clip's own frame orders (orders:) replace the suite's for it; a return: order's ranges must
// lie within the clip's frames, and no away:N (the suite has no other scene).
TEST(RealClipSuite, AClipMayNameItsOwnOrders) {
  const std::string range =
      "name: a\n    folder: a\n    first_frame: 10\n    last_frame: 19\n    references: [10, "
      "14]\n    cube: {edge: 0.1, base_centre: [0, 0, 0]}\n    wrong_px: 5\n";
  const RealClipSuite suite =
      parseRealClipSuite(oneClip(range + "    orders: [sequence, return:0-3+7-9+3-00]\n"), "S");
  EXPECT_EQ(suite.clips[0].orders, (std::vector<std::string>{"sequence", "return:0-3+7-9+3-0"}));
  EXPECT_TRUE(parseRealClipSuite(oneClip(kGood), "S").clips[0].orders.empty());
  const auto refused = [](const std::string& text) {
    return errorMessage([&] { parseRealClipSuite(text, "suite S"); });
  };
  std::string m = refused(oneClip(range + "    orders: [return:0-3+7-10+3-0]\n"));
  EXPECT_NE(m.find("line 9: clips[0].orders: bench-real: --order: 'return:0-3+7-10+3-0': the "
                   "range 7-10 reaches beyond the 10 frames"),
            std::string::npos)
      << m;
  m = refused(oneClip(range + "    orders: [away:5]\n"));
  EXPECT_NE(m.find("away:5: the suite plays no other scene (away:N)"), std::string::npos) << m;
  m = refused(oneClip(range + "    orders: []\n"));
  EXPECT_NE(m.find("clips[0].orders must be a list of one or more frame orders"), std::string::npos)
      << m;
  m = refused(oneClip(range + "    orders: [zigzag]\n"));
  EXPECT_NE(m.find("unknown order 'zigzag'"), std::string::npos) << m;
}

// Every mistake is refused with the line it is on and what is wrong.
TEST(RealClipSuite, ABadSuiteIsRefusedWithItsLine) {
  const auto refused = [](const std::string& text) {
    return errorMessage([&] { parseRealClipSuite(text, "suite S"); });
  };
  std::string m = refused(oneClip(kGood + "    wrong_pix: 5\n"));
  EXPECT_NE(m.find("suite S: line 7: clips[0].wrong_pix: unknown key"), std::string::npos) << m;
  EXPECT_NE(m.find("did you mean clips[0].wrong_px"), std::string::npos) << m;
  m = refused("clip:\n  - name: a\n");
  EXPECT_NE(m.find("line 1: clip: unknown key"), std::string::npos) << m;
  m = refused("");
  EXPECT_NE(m.find("no 'clips' list"), std::string::npos) << m;
  m = refused("clips: [\n");
  EXPECT_NE(m.find("suite S is not valid YAML: line"), std::string::npos) << m;
  // References outside the range, given twice, too few.
  m = refused(oneClip(
      "name: a\n    folder: a\n    first_frame: 180\n    last_frame: 300\n    references: [200, "
      "320]\n    cube: {edge: 0.1, base_centre: [0, 0, 0]}\n    wrong_px: 5\n"));
  EXPECT_NE(m.find("line 6: clips[0].references[1]: reference frame 320 is outside the clip's "
                   "frames 180..300"),
            std::string::npos)
      << m;
  m =
      refused(oneClip("name: a\n    folder: a\n    first_frame: 10\n    references: [0, 20]\n"
                      "    cube: {edge: 0.1, base_centre: [0, 0, 0]}\n    wrong_px: 5\n"));
  EXPECT_NE(m.find("line 5: clips[0].references[0]: reference frame 0 is outside the clip's "
                   "frames 10..the last"),
            std::string::npos)
      << m;
  std::string twice = kGood;
  twice.replace(twice.find("[0, 4]"), 6, "[4, 4]");
  EXPECT_NE(refused(oneClip(twice)).find("line 4: clips[0].references[1]: frame 4 given twice"),
            std::string::npos);
  std::string one = kGood;
  one.replace(one.find("[0, 4]"), 6, "[4]");
  EXPECT_NE(refused(oneClip(one)).find("line 4: clips[0].references must be a list of two"),
            std::string::npos);
  // A range backwards, a cube with both placements or none, a cube reaching behind the camera.
  m = refused(oneClip("name: a\n    folder: a\n    first_frame: 9\n    last_frame: 3\n" +
                      kGood.substr(kGood.find("    references"))));
  EXPECT_NE(m.find("line 5: clips[0].last_frame 3 is before first_frame 9"), std::string::npos)
      << m;
  std::string both = kGood;
  both.replace(both.find("base_centre: [0, 0, 0]"), 22,
               "base_centre: [0, 0, 0], in_front_of_reference: {distance: 1}");
  EXPECT_NE(refused(oneClip(both)).find("line 5: clips[0].cube: give one placement"),
            std::string::npos);
  std::string none = kGood;
  const std::string placement = ", base_centre: [0, 0, 0]";
  none.replace(none.find(placement), placement.size(), "");
  EXPECT_NE(refused(oneClip(none)).find("clips[0].cube: give one placement"), std::string::npos);
  std::string near = kGood;
  near.replace(near.find("base_centre: [0, 0, 0]"), 22, "in_front_of_reference: {distance: 0.04}");
  EXPECT_NE(refused(oneClip(near)).find("distance must exceed half the cube's edge"),
            std::string::npos);
  std::string centre = kGood;
  centre.replace(centre.find("[0, 0, 0]"), 9, "[0, 0]");
  EXPECT_NE(refused(oneClip(centre)).find("line 5: clips[0].cube.base_centre must be a list [x"),
            std::string::npos);
  // Missing or mistyped values; names and paths.
  std::string noWrong = kGood.substr(0, kGood.find("    wrong_px"));
  EXPECT_NE(refused(oneClip(noWrong)).find("line 2: clips[0]: 'wrong_px' is missing"),
            std::string::npos);
  std::string zeroWrong = kGood;
  zeroWrong.replace(zeroWrong.find("wrong_px: 5"), 11, "wrong_px: 0");
  EXPECT_NE(refused(oneClip(zeroWrong)).find("line 6: clips[0].wrong_px must be a number > 0"),
            std::string::npos);
  std::string quoted = kGood;
  quoted.replace(quoted.find("[0, 4]"), 6, "[0, \"4\"]");
  EXPECT_NE(refused(oneClip(quoted)).find("clips[0].references[1] must be a whole number >= 0"),
            std::string::npos);
  std::string absolute = kGood;
  absolute.replace(absolute.find("folder: a"), 9, "folder: /data/a");
  EXPECT_NE(refused(oneClip(absolute)).find("line 3: clips[0].folder: '/data/a' must be relative"),
            std::string::npos);
  std::string up = kGood;
  up.replace(up.find("folder: a"), 9, "folder: ../a");
  EXPECT_NE(refused(oneClip(up)).find("must not leave its folder"), std::string::npos);
  std::string badName = kGood;
  badName.replace(0, 7, "name: a b");
  EXPECT_NE(refused(oneClip(badName)).find("clips[0].name: 'a b' may hold letters"),
            std::string::npos);
  m = refused("clips:\n  - " + kGood + "  - " + kGood);
  EXPECT_NE(m.find("line 7: clips[1].name: 'a' is the name of the clip on line 2 too"),
            std::string::npos)
      << m;
}

TEST(RealClipSuite, AMissingFileIsNamed) {
  const auto dir = test::freshTempDir("RealClipSuite");
  const std::string m = errorMessage([&] { loadRealClipSuite(dir / "none.yml"); });
  EXPECT_NE(m.find("suite file '" + (dir / "none.yml").string() + "' not found"), std::string::npos)
      << m;
  std::ofstream(dir / "bad.yml") << oneClip(kGood + "    colour: red\n");
  const std::string bad = errorMessage([&] { loadRealClipSuite(dir / "bad.yml"); });
  EXPECT_NE(bad.find("suite file '" + (dir / "bad.yml").string() +
                     "': line 7: clips[0].colour: unknown key"),
            std::string::npos)
      << bad;
}

}  // namespace
}  // namespace reftrack::app
