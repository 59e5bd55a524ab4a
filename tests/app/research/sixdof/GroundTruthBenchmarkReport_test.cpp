#include "app/research/sixdof/GroundTruthBenchmarkReport.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"

namespace reftrack::app {
namespace {

// Four frames (frame 3 without a true pose), two methods in both orders.
GroundTruthBenchmarkResult smallResult() {
  GroundTruthBenchmarkResult r;
  r.framesDescription = "images 'frames' (4 frames)";
  r.groundTruthDescription = "TUM trajectory 'gt.txt' (3 poses)";
  r.frameSize = {752, 480};
  r.frames = 4;
  r.truth = {true, true, true, false};
  r.references = {0, 2};
  r.referenceDistancesMm = {0.0, 41.5};
  r.cubeCentre = {0.16, -0.10, 0.0};
  r.cubeEdge = 0.1;
  r.shuffleSeed = 7;
  r.passes = 1;
  r.mapPoints = 116;
  r.mapKeypoints = 6000;
  r.mapKeypointPoints = 248;
  r.modelPoints = {{"SIFT+PnP", 162}};
  r.orders = parseFrameOrders({"sequence", "shuffled"});
  auto run = [](const std::string& method, const std::string& order, std::vector<double> errors,
                std::vector<double> cpu) {
    MethodRun m;
    m.method = method;
    m.order = parseFrameOrder(order);
    m.plan = planFrames(m.order, 4, 7);
    m.errorPx = std::move(errors);
    m.poses.resize(m.errorPx.size());
    m.cpuMs = std::move(cpu);
    return m;
  };
  r.runs = {run("reftrack", "sequence", {0.2, 0.4, NAN, NAN}, {2, 2, 2, 2}),
            run("reftrack", "shuffled", {NAN, 6.0, 0.3, NAN}, {20, 20, 20, 20}),
            run("SIFT+PnP", "sequence", {0.5, 12.0, 1.0, 0.7}, {80, 80, 80, 80}),
            run("SIFT+PnP", "shuffled", {0.5, 12.0, 1.0, 0.7}, {90, 90, 90, 90}),
            run("ORB+PnP", "sequence", {INFINITY, 0.3, NAN, NAN}, {50, 50, 50, 50})};
  r.runs[0].predictedErrorPx = {0.2, 0.4, NAN, NAN};  // reftrack's prediction (sequence order)
  r.runs[0].uncertain = {false, false, false, false};
  r.runs[0].noPose["lost"] = 1;
  r.runs[1].noPose["relocalisation: not enough support"] = 1;
  r.seconds = 12.5;
  return r;
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(GroundTruthBenchmarkReport, TableHasARowPerMethodAndOrder) {
  const std::string table = groundTruthBenchmarkTable(smallResult());
  const std::vector<std::string> lines = linesOf(table);
  const auto header = std::find_if(lines.begin(), lines.end(),
                                   [](const std::string& l) { return l.rfind("method ", 0) == 0; });
  ASSERT_NE(header, lines.end()) << table;
  for (const char* column : {"order", "frames", "posed", "cover%", "mean_px", "p95_px", "max_px",
                             ">5px", "<=1.5px", "cpu_ms_med", "cpu_x"})
    EXPECT_NE(header->find(column), std::string::npos) << column;
  ASSERT_GE(lines.end() - header, 5);
  // reftrack, sequence: frames 0-2 scored (3 has no truth), 2 posed; cpu_x 1.
  std::istringstream row(*(header + 1));
  std::string method, order, mean, p95, max, ratio;
  int frames = 0, posed = 0, wrong = 0, good = 0;
  double cover = 0, cpu = 0;
  row >> method >> order >> frames >> posed >> cover >> mean >> p95 >> max >> wrong >> good >>
      cpu >> ratio;
  EXPECT_EQ(method, "reftrack");
  EXPECT_EQ(order, "sequence");
  EXPECT_EQ(frames, 3);
  EXPECT_EQ(posed, 2);
  EXPECT_NEAR(cover, 66.7, 1e-9);
  EXPECT_EQ(mean, "0.300");
  EXPECT_EQ(max, "0.40");
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(good, 2);
  EXPECT_DOUBLE_EQ(cpu, 2.0);
  EXPECT_EQ(ratio, "1.00");
  // SIFT, shuffled: 12 px is wrong, frame 3 (0.7, no truth) not scored; CPU 90 / reftrack's 20.
  EXPECT_NE(table.find("SIFT+PnP        shuffled       3       3  100.0    4.500"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("    1       2      90.00   4.50\n"), std::string::npos) << table;
  EXPECT_NE(table.find("references: frames 0 (0.0 mm from the first) 2 (41.5 mm"),
            std::string::npos);
  EXPECT_NE(table.find("reftrack map: 116 points; keypoint layer 6000 keypoints, 248 of them"),
            std::string::npos);
  EXPECT_NE(table.find("peers' triangulated points: SIFT+PnP 162"), std::string::npos);
  EXPECT_NE(table.find("no pose, reftrack shuffled: 1 x relocalisation: not enough support"),
            std::string::npos);
  EXPECT_NE(table.find("order seed 7"), std::string::npos);
  // The predicted error's calibration line: predictions 0.2 and 0.4, the true errors as large.
  EXPECT_NE(table.find("predicted cube error, reftrack sequence (issue 32): median 0.300, p95 "
                       "0.390, max 0.400 px over 2 frames; true / predicted median 1.00"),
            std::string::npos)
      << table;
  EXPECT_EQ(table.find("predicted cube error, reftrack shuffled"), std::string::npos);
  // A pose with the cube behind the camera: wrong, and named, but not in the mean.
  EXPECT_NE(table.find("ORB+PnP         sequence       3       2   66.7    0.300"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("ORB+PnP sequence: 1 pose(s) put the whole cube behind the camera"),
            std::string::npos)
      << table;
}

// The default orders print as they always have: the orders line and an 8-wide order column.
TEST(GroundTruthBenchmarkReport, DefaultOrdersKeepTheirHeader) {
  const std::string table = groundTruthBenchmarkTable(smallResult());
  EXPECT_NE(table.find("\nshuffled: every frame a cold start, order seed 7; CPU: thread time per "
                       "frame, one thread, 1 pass(es); cpu_x: median / reftrack's in the same "
                       "order\nmethod          order     frames"),
            std::string::npos)
      << table;
}

// Twelve frames, reftrack in shuffled-sequence, cuts:3 and stride:4: the order column widens to
// the longest name, stride scores only its frames, a cuts line gives each cut's frames to
// re-acquire and wrong poses, and the CSV columns name the orders.
TEST(GroundTruthBenchmarkReport, OtherOrdersAreNamedInTableAndCsv) {
  GroundTruthBenchmarkResult r = smallResult();
  r.frames = 12;
  r.truth.assign(12, true);
  r.orders = parseFrameOrders({"shuffled-sequence", "cuts:3", "stride:4"});
  r.runs.clear();
  for (const FrameOrder& order : r.orders) {
    MethodRun m;
    m.method = "reftrack";
    m.order = order;
    m.plan = planFrames(order, 12, 7);
    m.errorPx.assign(12, 0.5);
    m.poses.resize(12);
    m.cpuMs.assign(m.plan.frames.size(), 3.0);
    r.runs.push_back(m);
  }
  // cuts:3: the first frame after the first cut 8 px off, then 2 px, then good.
  MethodRun& cuts = r.runs[1];
  ASSERT_EQ(cuts.plan.cuts.size(), 2u);
  const std::size_t cut = cuts.plan.cuts[0];
  cuts.errorPx[static_cast<std::size_t>(cuts.plan.frames[cut])] = 8.0;
  cuts.errorPx[static_cast<std::size_t>(cuts.plan.frames[cut + 1])] = 2.0;
  const std::string table = groundTruthBenchmarkTable(r);
  EXPECT_NE(table.find("method          order              frames"), std::string::npos) << table;
  EXPECT_NE(table.find("reftrack        shuffled-sequence      12      12  100.0    0.500"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("reftrack        stride:4                3       3  100.0    0.500"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("shuffled-sequence: the shuffled order as one sequence, no reset; cuts:3: "
                       "3 segments of about 4 frames in a shuffled order, one sequence, no reset; "
                       "stride:4: frames 0, 4, 8, ... in order, one sequence (only those scored), "
                       "order seed 7"),
            std::string::npos)
      << table;
  const std::string cutsLine =
      "reftrack cuts:3: per cut @position frame->frame: re-acquired within k frames (<= 1.5 px), "
      "wrong (> 5 px) until the next cut: @4 " +
      std::to_string(cuts.plan.frames[cut - 1]) + "->" + std::to_string(cuts.plan.frames[cut]) +
      " k=2 wrong=1, @8 " + std::to_string(cuts.plan.frames[7]) + "->" +
      std::to_string(cuts.plan.frames[8]) +
      " k=0 wrong=0; max k=2, 1 wrong after the cuts (target: 0 wrong, every k <= 1)\n";
  EXPECT_NE(table.find(cutsLine), std::string::npos) << table << "\n" << cutsLine;

  const auto dir = test::freshTempDir("GroundTruthBenchmarkReportOrders");
  writeGroundTruthBenchmarkCsv(r, dir / "e.csv");
  const std::vector<std::string> csv = linesOf(test::readTextFile(dir / "e.csv"));
  ASSERT_EQ(csv.size(), 13u);
  EXPECT_EQ(csv[0],
            "frame,true_pose,reftrack_shuffled-sequence_px,reftrack_cuts:3_px,"
            "reftrack_stride:4_px");
  EXPECT_EQ(csv[2], "1,1,0.5,0.5,");  // frame 1: not played by stride:4
  EXPECT_EQ(csv[5], "4,1,0.5,0.5,0.5");
  // A segment never within 1.5 px after its cut: the worst is "never".
  GroundTruthBenchmarkResult worse = r;
  MethodRun& worseCuts = worse.runs[1];
  for (std::size_t i = 8; i < 12; ++i)
    worseCuts.errorPx[static_cast<std::size_t>(worseCuts.plan.frames[i])] = 7.0;
  const std::string never = groundTruthBenchmarkTable(worse);
  EXPECT_NE(never.find(" k=never(4) wrong=4; max k=never (1 of 2 cuts not re-acquired), 5 wrong "
                       "after the cuts"),
            std::string::npos)
      << never;
  writeGroundTruthBenchmarkPlot(r, dir / "e.png");
  EXPECT_FALSE(cv::imread((dir / "e.png").string()).empty());
}

// A return: order's lines: per range posed/plays, within 5 px, wrong (> wrong_px), the plays to
// the first pose within 5 px and the CPU; the frames between the start and the return with their
// share of a core; and, per run with recovery counts, what stopped each way back.
TEST(GroundTruthBenchmarkReport, ReturnRangesAndStopsAreReported) {
  MethodRun m;
  m.method = "reftrack";
  m.order = parseFrameOrder("return:0-1+5-6+1-0");
  m.plan = planFrames(m.order, 8, 1);
  //                play:  0    1    2    3     4    5
  m.playedErrorPx = {0.5, 0.5, NAN, 30.0, 6.0, 0.4};
  m.playedScored.assign(6, true);
  m.cpuMs = {1, 1, 3, 5, 2, 2};
  const std::string lines = returnLines(m, 30.0, 20.0, 100);
  EXPECT_NE(lines.find("reftrack return:0-1+5-6+1-0: per range (frames 100 on): posed, within 5 "
                       "px, wrong (> 20 px), the first pose within 5 px after k frames, CPU mean "
                       "per frame: 0-1 2/2 2 0 k=0 1.00 ms; 5-6 1/2 0 1 k=never 4.00 ms; 1-0 2/2 "
                       "1 0 k=1 2.00 ms\n"),
            std::string::npos)
      << lines;
  // Between: 2 frames at 4 ms mean = 12% of a core at 30 fps; the return's first play is 6 px off.
  EXPECT_NE(lines.find("reftrack return:0-1+5-6+1-0: between the start and the return 2 frames, 1 "
                       "posed, 1 wrong (target 0); CPU mean 4.00 ms per frame = 12.0% of one "
                       "core at 30 fps; the return: first pose within 5 px after 1 frames, 0 "
                       "wrong\n"),
            std::string::npos)
      << lines;
  MethodRun sequence = m;
  sequence.order = parseFrameOrder("sequence");
  EXPECT_EQ(returnLines(sequence, 30.0, 20.0, 0), "");

  EXPECT_EQ(stopLines({m}, "desk: "), "");  // no recovery counts: no line
  m.startStops = {{"no start pose", 3}};
  m.searchStops = {{"PnP inliers", 2}, {"verified", 1}};
  m.searchCpuMs = {40.0, 10.0, 30.0};
  EXPECT_EQ(stopLines({m}, "desk: "),
            "desk: reftrack return:0-1+5-6+1-0: per frame not tracked, the start near a "
            "reference: no start pose 3\n"
            "desk: reftrack return:0-1+5-6+1-0: relocalisation attempts, what stopped each: PnP "
            "inliers 2, verified 1; thread CPU per attempt with its verification: median 30.0 "
            "ms\n");
}

TEST(GroundTruthBenchmarkReport, WritesTableCsvAndPlotIntoTheFolder) {
  const auto dir = test::freshTempDir("GroundTruthBenchmarkReport") / "out";
  const GroundTruthBenchmarkResult r = smallResult();
  const GroundTruthBenchmarkFiles files = writeGroundTruthBenchmarkFiles(r, dir);
  EXPECT_EQ(files.table, dir / "table.txt");
  EXPECT_EQ(test::readTextFile(files.table), groundTruthBenchmarkTable(r));
  const std::vector<std::string> csv = linesOf(test::readTextFile(files.csv));
  ASSERT_EQ(csv.size(), 5u);
  EXPECT_EQ(csv[0],
            "frame,true_pose,reftrack_sequence_px,reftrack_shuffled_px,sift_pnp_sequence_px,"
            "sift_pnp_shuffled_px,orb_pnp_sequence_px,reftrack_sequence_predicted_px");
  EXPECT_EQ(csv[1], "0,1,0.2,,0.5,0.5,inf,0.2");
  EXPECT_EQ(csv[4], "3,0,,,0.7,0.7,,");
  const cv::Mat plot = cv::imread(files.plot.string());
  ASSERT_FALSE(plot.empty());
  EXPECT_EQ(plot.size(), cv::Size(1200, 600));
  // Nothing else is left in the folder (no temporary files).
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 3);
}

// The plot's peer: SIFT posed all 3 scored frames (mean 4.5 px, one 12 px pose), ORB 2 of 3 (one
// behind the camera): SIFT. An ORB that poses every frame more precisely is the better one.
TEST(GroundTruthBenchmarkReport, TheBestPeerIsTheMostAccurateOfThoseThatPoseNearlyEveryFrame) {
  GroundTruthBenchmarkResult r = smallResult();
  EXPECT_EQ(bestPeerRun(r, "sequence"), std::optional<std::size_t>(2));
  EXPECT_EQ(bestPeerRun(r, "shuffled"), std::optional<std::size_t>(3));
  EXPECT_EQ(bestPeerRun(r, "stride:2"), std::nullopt);
  r.runs[4].errorPx = {0.3, 0.3, 0.4, NAN};
  EXPECT_EQ(bestPeerRun(r, "sequence"), std::optional<std::size_t>(4));
  // None near full coverage: the one that posed the most.
  r.runs[2].errorPx = {0.5, NAN, NAN, NAN};
  r.runs[4].errorPx = {0.3, 0.3, NAN, NAN};
  EXPECT_EQ(bestPeerRun(r, "sequence"), std::optional<std::size_t>(4));
}

// A clip read from frame 180 (`bench-real --suite`): the table, the CSV and the cut lines name
// the input's frames; a cube in front of the first reference is described as such; a map the
// preparation refused, or none needed, is said so.
TEST(GroundTruthBenchmarkReport, ARangeOfFramesIsNumberedAsInTheInput) {
  GroundTruthBenchmarkResult r = smallResult();
  r.firstFrame = 180;
  r.cubeInFrontM = 1.0;
  r.cube =
      cubeInFrontOf(RigidPose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.5, 0, 0)), 1.0, 0.1);
  std::string table = groundTruthBenchmarkTable(r);
  EXPECT_NE(table.find("frames: 4 (180-183) of images 'frames' (4 frames)"), std::string::npos)
      << table;
  EXPECT_NE(table.find("references: frames 180 (0.0 mm from the first) 182 (41.5 mm"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("cube: centred 1.000 m in front of reference frame 180's camera on its "
                       "optical axis, edges along its axes (centre (-0.500, 0.000, 1.000) m in "
                       "the world), edge 0.100 m; error: "),
            std::string::npos)
      << table;
  const auto dir = test::freshTempDir("GroundTruthBenchmarkReportRange");
  writeGroundTruthBenchmarkCsv(r, dir / "e.csv");
  const std::vector<std::string> csv = linesOf(test::readTextFile(dir / "e.csv"));
  ASSERT_EQ(csv.size(), 5u);
  EXPECT_EQ(csv[1].rfind("180,1,", 0), 0u) << csv[1];
  EXPECT_EQ(csv[4].rfind("183,0,", 0), 0u) << csv[4];
  r.mapError = "only 12 map points";
  table = groundTruthBenchmarkTable(r);
  EXPECT_NE(table.find("reftrack map: none, the preparation refused it: only 12 map points\n"),
            std::string::npos)
      << table;
  r.runs.erase(r.runs.begin(), r.runs.begin() + 2);  // no reftrack run
  EXPECT_FALSE(usesMap(r));
  EXPECT_NE(groundTruthBenchmarkTable(r).find("reftrack map: not prepared"), std::string::npos);
}

TEST(GroundTruthBenchmarkReport, AnUnusableFolderIsAnError) {
  const auto dir = test::freshTempDir("GroundTruthBenchmarkReportBad");
  std::ofstream(dir / "file") << "x";
  const std::string m =
      test::errorMessage([&] { writeGroundTruthBenchmarkFiles(smallResult(), dir / "file"); });
  EXPECT_NE(m.find("cannot create the output folder"), std::string::npos) << m;
}

}  // namespace
}  // namespace reftrack::app
