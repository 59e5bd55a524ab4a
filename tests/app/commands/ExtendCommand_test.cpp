// `reftrack extend` end to end: a two-reference map of the simulator's desk scene (exact reference
// poses) is extended from an orbit that leaves the references' volume; the added references are
// checked against the simulator's ground truth, the anchored ones must not move.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include "CommandTestSupport.hpp"
#include "TestPaths.hpp"
#include "engine/geometry/TumTrajectory.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

using namespace reftrack;
using namespace reftrack::test;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;

// One simulated orbit and its prepared two-reference map for the whole suite.
class ExtendCommandTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(freshTempDir("ExtendCommand_sim"));
    const CommandRun sim =
        runReftrack("simulate --preset orbit --frames " + std::to_string(kSimFrames) +
                        " --size 640x480 --out " + (*dir_ / "sim").string(),
                    *dir_);
    ASSERT_EQ(sim.exitCode, 0) << sim.err;
    const fs::path s = *dir_ / "sim";
    const CommandRun prep = runReftrack(
        "prepare --camera " + (s / "camera.yml").string() + " --ref-a " +
            (s / "reference_a.png").string() + " --ref-b " + (s / "reference_b.png").string() +
            " --poses " + (s / "references.txt").string() + " --out " + (*dir_ / "map").string(),
        *dir_);
    ASSERT_EQ(prep.exitCode, 0) << prep.err;
  }
  static void TearDownTestSuite() { delete dir_; }

  // The orbit swings 75 degrees out and back over a quarter of the frames each way; the first 30
  // frames turn 75 degrees away from A. 640x480: at 320x240 the tracker keeps only 43% of these
  // fast orbit frames (measured), so the test renders 120 frames at 640x480 (~25 s of CPU).
  static constexpr int kSimFrames = 120;
  static constexpr int kExtendFrames = 30;
  static fs::path* dir_;
};
fs::path* ExtendCommandTest::dir_ = nullptr;

struct AddedLine {
  int view = -1, frame = -1;
};

std::vector<AddedLine> addedReferences(const std::string& out) {
  std::vector<AddedLine> added;
  const std::regex line(R"(reference (\d+) \([^)]*\) from frame (\d+))");
  for (auto it = std::sregex_iterator(out.begin(), out.end(), line); it != std::sregex_iterator();
       ++it)
    added.push_back({std::stoi((*it)[1]), std::stoi((*it)[2])});
  return added;
}

}  // namespace

TEST_F(ExtendCommandTest, AddsReferencesWhereTheOrbitLeavesTheMapAtTheirTruePoses) {
  const fs::path out = freshTempDir("ExtendCommand_orbit") / "map2";
  const CommandRun run = runReftrack("extend --map " + (*dir_ / "map").string() + " --input " +
                                         (*dir_ / "sim" / "frames").string() + " --frames " +
                                         std::to_string(kExtendFrames) + " --out " + out.string(),
                                     out.parent_path());
  ASSERT_EQ(run.exitCode, 0) << run.err << run.out;
  std::cout << run.out;
  const MultiReferenceMap before = MultiReferenceMap::load(*dir_ / "map");
  const MultiReferenceMap after = MultiReferenceMap::load(out);
  const TumTrajectory truth = TumTrajectory::load(*dir_ / "sim" / "groundtruth.txt");
  ASSERT_EQ(truth.poses.size(), static_cast<std::size_t>(kSimFrames));

  // The orbit turns 75 degrees away from references about 14 degrees apart: several are added.
  ASSERT_GE(after.size(), before.size() + 2) << run.out;
  EXPECT_GT(after.points.size(), before.points.size());
  // The anchored references are where they were, bit for bit.
  for (int v = 0; v < before.size(); ++v) {
    EXPECT_TRUE(after.views[v].anchored);
    EXPECT_EQ(after.views[v].T.matrix4(), before.views[v].T.matrix4()) << v;
  }
  const std::vector<AddedLine> added = addedReferences(run.out);
  ASSERT_EQ(static_cast<int>(added.size()), after.size() - before.size()) << run.out;
  for (const AddedLine& a : added) {
    ASSERT_LT(a.view, after.size());
    ASSERT_LT(a.frame, kExtendFrames);
    const ReferenceView& v = after.views[static_cast<std::size_t>(a.view)];
    EXPECT_FALSE(v.anchored);
    const RigidPose& T = truth.poses[static_cast<std::size_t>(a.frame)].worldToCamera;
    const double mm = RigidPose::translationDistance(v.T.inverse(), T.inverse()) * 1e3;
    const double deg = RigidPose::rotationDistance(v.T, T) * 180.0 / kPi;
    // A few millimetres (issue 13). Measured 0.8-0.9 mm and 0.03-0.05 degrees for the three
    // references this run adds (frames 10, 16, 24); 3 mm / 0.15 degrees leave room for other
    // tracker and detector versions.
    EXPECT_LT(mm, 3.0) << "reference " << a.view << " from frame " << a.frame;
    EXPECT_LT(deg, 0.15) << "reference " << a.view << " from frame " << a.frame;
  }
  EXPECT_NE(run.out.find("final bundle adjustment"), std::string::npos);
  EXPECT_NE(run.out.find("wrote " + out.string()), std::string::npos);
}

// Its own small map (4 frames at 320x240: ~2 s) rather than the orbit's (CTest runs each test in
// a process of its own, so a shared suite's set-up, ~28 s, is paid by every test of it).
TEST(ExtendCommandErrors, BadArgumentsAreUsageErrorsAndBadInputIsNamed) {
  const fs::path dir = freshTempDir("ExtendCommand_errors");
  const CommandRun sim = runReftrack(
      "simulate --preset orbit --frames 4 --size 320x240 --out " + (dir / "sim").string(), dir);
  ASSERT_EQ(sim.exitCode, 0) << sim.err;
  const fs::path s = dir / "sim";
  const CommandRun prep = runReftrack(
      "prepare --camera " + (s / "camera.yml").string() + " --ref-a " +
          (s / "reference_a.png").string() + " --ref-b " + (s / "reference_b.png").string() +
          " --poses " + (s / "references.txt").string() + " --out " + (dir / "map").string(),
      dir);
  ASSERT_EQ(prep.exitCode, 0) << prep.err;
  const std::string map = (dir / "map").string();
  const std::string frames = (s / "frames").string();
  // Usage errors: exit 2.
  EXPECT_EQ(
      runReftrack("extend --input " + frames + " --out " + (dir / "o").string(), dir).exitCode, 2);
  EXPECT_EQ(runReftrack("extend --map " + map + " --out " + (dir / "o").string(), dir).exitCode, 2);
  EXPECT_EQ(runReftrack("extend --map " + map + " --input " + frames, dir).exitCode, 2);
  EXPECT_EQ(runReftrack("extend --map " + (dir / "missing").string() + " --input " + frames +
                            " --out " + (dir / "o").string(),
                        dir)
                .exitCode,
            2);
  EXPECT_EQ(runReftrack("extend --map " + map + " --input " + frames + " --frames 0 --out " +
                            (dir / "o").string(),
                        dir)
                .exitCode,
            2);
  // A bad extension parameter: exit 1 naming the field; nothing written.
  std::ofstream(dir / "bad.yml") << "%YAML:1.0\nextension:\n  max_angle_deg: -3\n";
  const CommandRun bad =
      runReftrack("extend --map " + map + " --input " + frames + " --extend-params " +
                      (dir / "bad.yml").string() + " --out " + (dir / "o").string(),
                  dir);
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.err.find("extension.max_angle_deg"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "o"));
  // A folder that is not a map: exit 1 naming it.
  const CommandRun notMap = runReftrack(
      "extend --map " + dir.string() + " --input " + frames + " --out " + (dir / "o").string(),
      dir);
  EXPECT_EQ(notMap.exitCode, 1);
  EXPECT_NE(notMap.err.find(dir.string()), std::string::npos) << notMap.err;
  // An input that does not exist: exit 1 naming it.
  const CommandRun noInput =
      runReftrack("extend --map " + map + " --input " + (dir / "nothing.mp4").string() + " --out " +
                      (dir / "o").string(),
                  dir);
  EXPECT_EQ(noInput.exitCode, 1);
  EXPECT_NE(noInput.err.find("nothing.mp4"), std::string::npos) << noInput.err;
  EXPECT_FALSE(fs::exists(dir / "o"));
}
