#include "app/research/sixdof/RealClipSuiteReport.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"

namespace reftrack::app {
namespace {

MethodRun run(const std::string& method, const std::string& order, std::vector<double> errors,
              std::vector<double> cpu) {
  MethodRun m;
  m.method = method;
  m.order = parseFrameOrder(order);
  m.plan = planFrames(m.order, static_cast<int>(errors.size()), 1);
  m.errorPx = std::move(errors);
  m.poses.resize(m.errorPx.size());
  m.cpuMs = std::move(cpu);
  return m;
}

// Two clips of four frames, reftrack and SIFT (and on the second ORB) in order and shuffled as
// one sequence; a third clip skipped.
RealClipSuiteResult smallSuite() {
  RealClipSuiteResult result;
  result.suiteDescription = "suite file 'real-clips.yml'";
  result.dataRoot = "../shared/data";
  result.orders = {"sequence", "shuffled-sequence"};
  result.skipped = {"shelf: its folder '../shared/data/shelf' is missing"};
  const auto clip = [&](const std::string& name, double wrongPx, int firstFrame) {
    RealClipRun c;
    c.clip.name = name;
    c.clip.wrongPx = wrongPx;
    GroundTruthBenchmarkResult& r = c.benchmark;
    r.frames = 4;
    r.firstFrame = firstFrame;
    r.frameSize = {640, 480};
    r.truth.assign(4, true);
    r.references = {0, 2};
    r.referenceDistancesMm = {0.0, 41.5};
    r.cubeEdge = 0.1;
    r.shuffleSeed = 1;
    r.orders = parseFrameOrders(result.orders);
    r.mapPoints = 116;
    r.modelPoints = {{"SIFT+PnP", 500}};
    c.peerSources = {"SIFT+PnP: cached"};
    c.peersFromCache = true;
    return c;
  };
  RealClipRun desk = clip("desk", 5.0, 0);
  desk.benchmark.runs = {
      run("reftrack", "sequence", {0.2, 0.4, NAN, 6.0}, {1, 2, 3, 4}),
      run("reftrack", "shuffled-sequence", {0.2, 0.4, 0.3, 0.5}, {9, 9, 9, 9}),
      run("SIFT+PnP", "sequence", {0.1, 0.1, 0.1, 0.1}, {100, 100, 100, 100}),
      run("SIFT+PnP", "shuffled-sequence", {0.1, 0.1, 0.1, 0.1}, {100, 100, 100, 100})};
  desk.benchmark.runs[0].predictedErrorPx = {0.2, 0.2, NAN, 2.0};  // true / predicted 1, 2, 3
  RealClipRun kinect = clip("kinect", 20.0, 180);
  kinect.benchmark.cubeInFrontM = 1.0;
  kinect.benchmark.cube = cubeInFrontOf(RigidPose(), 1.0, 0.1);
  kinect.peersFromCache = false;
  kinect.benchmark.runs = {
      run("reftrack", "sequence", {3.0, 30.0, NAN, NAN}, {5, 5, 5, 5}),
      run("reftrack", "shuffled-sequence", {3.0, 30.0, NAN, NAN}, {5, 5, 5, 5}),
      run("SIFT+PnP", "sequence", {4.0, 4.0, 25.0, NAN}, {100, 100, 100, 100}),
      run("SIFT+PnP", "shuffled-sequence", {4.0, 4.0, 25.0, NAN}, {100, 100, 100, 100}),
      run("ORB+PnP", "sequence", {4.0, NAN, NAN, NAN}, {50, 50, 50, 50}),
      run("ORB+PnP", "shuffled-sequence", {4.0, NAN, NAN, NAN}, {50, 50, 50, 50})};
  result.clips = {desk, kinect};
  return result;
}

// The whitespace-separated fields of the table row of clip, order and method.
std::vector<std::string> row(const std::string& table, const std::string& clip,
                             const std::string& order, const std::string& method) {
  std::istringstream lines(table);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream in(line);
    std::vector<std::string> fields;
    for (std::string f; in >> f;) fields.push_back(f);
    if (fields.size() == 13 && fields[0] == clip && fields[1] == order && fields[2] == method)
      return {fields.begin() + 3, fields.end()};
  }
  return {};
}

TEST(RealClipSuiteReport, OneTableOverEveryClipOrderAndMethod) {
  const std::string table = realClipSuiteTable(smallSuite());
  EXPECT_NE(table.find("suite: suite file 'real-clips.yml', data ../shared/data; 2 clip(s) run, 1 "
                       "skipped\nskipped: shelf: its folder '../shared/data/shelf' is missing\n"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("\nclip   order             method          frames tracked posed%  mean_px"
                       "   p95_px  <=5px wrong  >px true/pred ms/frame\n"),
            std::string::npos)
      << table;
  // frames, tracked, posed%, mean, p95, <=5px, wrong, >px, true/pred, ms/frame.
  // desk in order: 0.2, 0.4, 6 px: p95 0.4 + 0.9 x 5.6 (linear between the sorted errors).
  EXPECT_EQ(row(table, "desk", "sequence", "reftrack"),
            (std::vector<std::string>{"4", "3", "75.0", "2.200", "5.440", "2", "1", "5", "2.00",
                                      "2.50"}));
  EXPECT_EQ(row(table, "desk", "sequence", "SIFT+PnP"),
            (std::vector<std::string>{"4", "4", "100.0", "0.100", "0.100", "4", "0", "5", "-",
                                      "100.00"}));
  // The Kinect: within 5 px and wrong (> 20 px) counted against its own threshold.
  const std::vector<std::string> kinect = row(table, "kinect", "shuffled-sequence", "reftrack");
  ASSERT_EQ(kinect.size(), 10u) << table;
  EXPECT_EQ(kinect[1], "2");
  EXPECT_EQ(kinect[3], "16.500");
  EXPECT_EQ(kinect[5], "1");  // 3 px
  EXPECT_EQ(kinect[6], "1");  // 30 px > 20
  EXPECT_EQ(kinect[7], "20");
  EXPECT_EQ(kinect[8], "-");  // no prediction
  const std::vector<std::string> sift = row(table, "kinect", "sequence", "SIFT+PnP");
  ASSERT_EQ(sift.size(), 10u);
  EXPECT_EQ(sift[5], "2");
  EXPECT_EQ(sift[6], "1");  // 25 px
  // A legend line per clip, the orders and where the peers' poses came from.
  EXPECT_NE(table.find("desk: frames 0-3 (4 with a true pose), 640x480; references 0, 2 (41.5 mm "
                       "apart); cube base centre (0.000, 0.000, 0.000) m, edge 0.100 m; wrong: > "
                       "5 px\n  reftrack map 116 points (keypoint layer: 0 with a 3D point); "
                       "peers' triangulated points: SIFT+PnP 500 (poses from the cache)\n"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("kinect: frames 180-183 (4 with a true pose), 640x480; references 180, 182 "
                       "(41.5 mm apart); cube centred 1.000 m in front of reference frame 180's "
                       "camera on its optical axis"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("(poses computed)"), std::string::npos);
  EXPECT_NE(table.find("orders: sequence: every frame in order; shuffled-sequence: the frames in "
                       "a shuffled order played as one sequence, no reset (every frame a jump) "
                       "(shuffle seed 1)\n"),
            std::string::npos)
      << table;
}

// Per order the clip where reftrack's mean is furthest above its best peer's, and the last line
// the worst of all, naming clip, order and peer. On the Kinect no peer posed 90% of the frames:
// the best is the one that posed the most (SIFT).
TEST(RealClipSuiteReport, TheLastLineIsTheWorstClipAgainstItsBestPeer) {
  const RealClipSuiteResult suite = smallSuite();
  const std::vector<SuiteRatio> ratios = suiteRatios(suite);
  ASSERT_EQ(ratios.size(), 4u);
  EXPECT_EQ(ratios[2].clip, "kinect");
  EXPECT_EQ(ratios[2].peer, "SIFT+PnP");
  EXPECT_NEAR(ratios[2].ratio, 16.5 / 11.0, 1e-12);
  const std::string table = realClipSuiteTable(suite);
  EXPECT_NE(table.find("\nworst clip in sequence order: desk (sequence): reftrack mean 2.200 px / "
                       "its best peer SIFT+PnP 0.100 px = 22.00\nworst clip in shuffled-sequence "
                       "order: desk (shuffled-sequence): reftrack mean 0.350 px / its best peer "
                       "SIFT+PnP 0.100 px = 3.50\n"),
            std::string::npos)
      << table;
  const std::string last =
      "worst clip: desk (sequence): reftrack mean 2.200 px / its best peer "
      "SIFT+PnP 0.100 px = 22.00\n";
  ASSERT_GE(table.size(), last.size());
  EXPECT_EQ(table.substr(table.size() - last.size()), last) << table;
  // reftrack posing nothing is the worst there is.
  RealClipSuiteResult lost = suite;
  lost.clips[1].benchmark.runs[0].errorPx.assign(4, NAN);
  const std::optional<SuiteRatio> worst = worstRatio(suiteRatios(lost));
  ASSERT_TRUE(worst);
  EXPECT_EQ(worst->clip, "kinect");
  EXPECT_TRUE(std::isinf(worst->ratio));
  const std::string lostTable = realClipSuiteTable(lost);
  EXPECT_NE(lostTable.find("worst clip with a sub-pixel truth (wrong_px <= 5): desk (sequence): "
                           "reftrack mean 2.200 px / its best peer SIFT+PnP 0.100 px = 22.00\n"
                           "worst clip: kinect (sequence): reftrack posed no frame / its best peer "
                           "SIFT+PnP 11.000 px = inf\n"),
            std::string::npos)
      << lostTable;
  // The worst clip has a sub-pixel truth itself: no separate line.
  EXPECT_EQ(table.find("sub-pixel truth"), std::string::npos) << table;
  EXPECT_EQ(worstRatio(ratios, "", 5.0)->clip, "desk");
  EXPECT_NEAR(worstRatio(ratios, "shuffled-sequence", 5.0)->ratio, 3.5, 1e-12);
}

TEST(RealClipSuiteReport, WritesTheTableAndEachClipsFiles) {
  const auto dir = test::freshTempDir("RealClipSuiteReport") / "out";
  const RealClipSuiteResult suite = smallSuite();
  const RealClipSuiteFiles files = writeRealClipSuiteFiles(suite, dir);
  EXPECT_EQ(files.table, dir / "table.txt");
  EXPECT_EQ(test::readTextFile(files.table), realClipSuiteTable(suite));
  ASSERT_EQ(files.clipDirs.size(), 2u);
  EXPECT_EQ(files.clipDirs[1], dir / "kinect");
  for (const auto& clip : files.clipDirs) {
    EXPECT_TRUE(std::filesystem::is_regular_file(clip / "table.txt")) << clip;
    EXPECT_FALSE(cv::imread((clip / "cube_errors.png").string()).empty()) << clip;
  }
  // The CSV names the input's frames: the Kinect clip's start at 180.
  const std::string csv = test::readTextFile(dir / "kinect" / "cube_errors.csv");
  EXPECT_NE(csv.find("\n180,1,3,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n183,1,"), std::string::npos) << csv;
  std::ofstream(dir.parent_path() / "file") << "x";
  EXPECT_NE(test::errorMessage([&] {
              writeRealClipSuiteFiles(suite, dir.parent_path() / "file");
            }).find("cannot create the output folder"),
            std::string::npos);
}

}  // namespace
}  // namespace reftrack::app
