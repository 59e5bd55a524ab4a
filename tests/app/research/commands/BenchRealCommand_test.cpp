#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <tuple>

#include "TestPaths.hpp"
#include "app/commands/CommandTestSupport.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/TumTrajectory.hpp"

using namespace reftrack::test;

// A few frames of the real postcard clip: the command prints both trackers' rows and the ratio.
TEST(BenchRealCommand, PrintsBothTrackersAndTheRatioOnThePostcardClip) {
  const auto data = sharedDataDir();
  const auto clip = data ? *data / "planar-videos" / "video-postcard.mp4" : std::filesystem::path();
  if (!data || !std::filesystem::exists(clip))
    GTEST_SKIP() << "../shared/data/planar-videos/video-postcard.mp4 not available";
  const auto dir = freshTempDir("BenchRealCommand");
  const auto r = runReftrack("bench-real --clip " + clip.string() + " --frames 8 --passes 1", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("card followed in"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("reftrack 6-DOF"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ORB+PnP+Kalman"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("speed ratio baseline / reftrack"), std::string::npos) << r.out;
}

TEST(BenchRealCommand, MissingClipIsAClearErrorAndBadReferencesAUsageError) {
  const auto dir = freshTempDir("BenchRealCommandErrors");
  const auto missing = runReftrack("bench-real --clip " + (dir / "none.mp4").string(), dir);
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_NE(missing.err.find("not found"), std::string::npos) << missing.err;
  EXPECT_NE(missing.err.find("none.mp4"), std::string::npos) << missing.err;
  EXPECT_EQ(runReftrack("bench-real --references 5", dir).exitCode, 2);
  EXPECT_EQ(runReftrack("bench-real --references 5,5", dir).exitCode, 2);
  EXPECT_EQ(runReftrack("bench-real --target 1,2,3", dir).exitCode, 2);
}

namespace {

// The rows of the table `bench-real --input` prints: method, order -> the numbers after them.
std::map<std::string, std::vector<std::string>> tableRows(const std::string& out) {
  std::map<std::string, std::vector<std::string>> rows;
  std::istringstream in(out);
  bool inTable = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("method ", 0) == 0) {
      inTable = true;
      continue;
    }
    if (!inTable) continue;
    std::istringstream fields(line);
    std::string method, order;
    fields >> method >> order;
    const bool isOrder = (order == "sequence" || order.rfind("shuffled", 0) == 0 ||
                          order.rfind("cuts:", 0) == 0 || order.rfind("stride:", 0) == 0) &&
                         order.back() != ':';  // not the line of a cuts:N run
    if (!isOrder) break;
    std::vector<std::string> numbers;
    for (std::string f; fields >> f;) numbers.push_back(f);
    rows[method + " " + order] = numbers;
  }
  return rows;
}

// The per-frame errors of one CSV column (NaN where empty), and the true_pose column.
std::vector<double> csvColumn(const std::filesystem::path& csv, const std::string& name) {
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  std::vector<std::string> names;
  std::istringstream h(header);
  for (std::string n; std::getline(h, n, ',');) names.push_back(n);
  const auto at = std::find(names.begin(), names.end(), name);
  if (at == names.end()) return {};
  const std::size_t column = static_cast<std::size_t>(at - names.begin());
  std::vector<double> values;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::istringstream l(line);
    for (std::string c; std::getline(l, c, ',');) cells.push_back(c);
    values.push_back(column < cells.size() && !cells[column].empty() ? std::stod(cells[column])
                                                                     : NAN);
  }
  return values;
}

}  // namespace

// The real desk clip (../shared/data/desk-chessboard), its first 20 frames (reading 41 for
// reference 40; all 400 take minutes), references 0 and 40 with their true poses: the table has
// every method in both orders, the files are written, and the per-frame OpenCV peers are working
// pipelines here. Measured on these frames: SIFT 20/20 posed, cube error mean 0.30 px, max 0.53;
// AKAZE 20/20, 0.16, max 0.24; ORB 20/20, 0.37, max 0.78 (over the first 60: 0.56 / 1.22,
// 0.24 / 0.42, 0.77 / 3.59; the several-pixel errors come later in the clip). Bounds:
// every frame posed by SIFT and AKAZE, at least 18 by ORB, mean below 1 px (1.5 for ORB) and none
// more than 5 px off: about 3x the measured means, while a broken pipeline (wrong references,
// distortion ignored, the wrong frame's truth) is pixels off or loses frames. reftrack's numbers
// are not bounded here (the engine is being changed; its own real-data tests hold its targets).
TEST(BenchRealCommand, DeskClipTableFilesAndPlausiblePeers) {
  const auto data = sharedDataDir();
  const auto desk = data ? *data / "desk-chessboard" : std::filesystem::path();
  if (!data || !std::filesystem::is_directory(desk / "frames"))
    GTEST_SKIP() << "../shared/data/desk-chessboard not available (the shared real recordings)";
  const auto dir = freshTempDir("BenchRealCommandDesk");
  const auto r = runReftrack("bench-real --input " + (desk / "frames").string() + " --camera " +
                                 (desk / "camera.yml").string() + " --gt " +
                                 (desk / "groundtruth.txt").string() +
                                 " --ref-frames 0,40 --cube-centre 0.16,-0.10,0 --cube-edge 0.1"
                                 " --frames 20 --out " +
                                 (dir / "out").string(),
                             dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = tableRows(r.out);
  for (const char* method : {"reftrack", "SIFT+PnP", "AKAZE+PnP", "ORB+PnP", "ORB+PnP+Kalman"})
    for (const char* order : {"sequence", "shuffled"}) {
      const std::string key = std::string(method) + " " + order;
      ASSERT_EQ(rows.count(key), 1u) << key << "\n" << r.out;
      const std::vector<std::string>& row = rows.at(key);
      ASSERT_EQ(row.size(), 10u) << key;  // frames posed cover% mean p95 max >5 <=1.5 cpu cpu_x
      EXPECT_EQ(row[0], "20") << key;
    }
  EXPECT_NE(r.out.find("references: frames 0 (0.0 mm from the first) 40 ("), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("reftrack map: "), std::string::npos);
  EXPECT_NE(r.out.find("peers' triangulated points: SIFT+PnP "), std::string::npos);
  EXPECT_NE(r.out.find("wrote the table " + (dir / "out" / "table.txt").string()),
            std::string::npos)
      << r.out;
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out" / "cube_errors.png"));
  const auto csv = dir / "out" / "cube_errors.csv";
  for (const auto& [column, minPosed, maxMean] :
       {std::tuple{"sift_pnp_sequence_px", 20, 1.0}, std::tuple{"akaze_pnp_sequence_px", 20, 1.0},
        std::tuple{"orb_pnp_sequence_px", 18, 1.5}}) {
    const std::vector<double> e = csvColumn(csv, column);
    ASSERT_EQ(e.size(), 20u) << column;
    int posed = 0;
    double sum = 0, worst = 0;
    for (double v : e)
      if (!std::isnan(v)) ++posed, sum += v, worst = std::max(worst, v);
    EXPECT_GE(posed, minPosed) << column;
    ASSERT_GT(posed, 0) << column;
    EXPECT_LT(sum / posed, maxMean) << column;
    EXPECT_LE(worst, 5.0) << column;
    // The shuffled run is the same per-frame pipeline: the same errors frame by frame.
    std::string shuffled = column;
    shuffled.replace(shuffled.find("sequence"), 8, "shuffled");
    const std::vector<double> s = csvColumn(csv, shuffled);
    ASSERT_EQ(s.size(), 20u);
    for (std::size_t k = 0; k < 20; ++k)
      if (!std::isnan(e[k]) || !std::isnan(s[k])) {
        EXPECT_NEAR(e[k], s[k], 1e-6) << column << k;
      }
  }
}

// reftrack alone on the desk clip's first 24 frames in the other orders: a row per order (stride:5
// scores its 5 frames only), a line of the cuts:3 run's two cuts, and CSV columns named by order
// whose stride column is empty on the frames not played. The numbers are not bounded here (the
// engine is being changed); the order logic is tested in FrameOrder_test and
// GroundTruthBenchmark_test.
TEST(BenchRealCommand, DeskClipOrdersForReftrackAlone) {
  const auto data = sharedDataDir();
  const auto desk = data ? *data / "desk-chessboard" : std::filesystem::path();
  if (!data || !std::filesystem::is_directory(desk / "frames"))
    GTEST_SKIP() << "../shared/data/desk-chessboard not available (the shared real recordings)";
  const auto dir = freshTempDir("BenchRealCommandDeskOrders");
  const auto r = runReftrack(
      "bench-real --input " + (desk / "frames").string() + " --camera " +
          (desk / "camera.yml").string() + " --gt " + (desk / "groundtruth.txt").string() +
          " --ref-frames 0,40 --cube-centre 0.16,-0.10,0 --cube-edge 0.1 --frames 24"
          " --methods reftrack --order sequence,shuffled-sequence,cuts:3,stride:5 --out " +
          (dir / "out").string(),
      dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = tableRows(r.out);
  EXPECT_EQ(rows.size(), 4u) << r.out;
  for (const auto& [order, frames] :
       {std::pair{"sequence", "24"}, std::pair{"shuffled-sequence", "24"},
        std::pair{"cuts:3", "24"}, std::pair{"stride:5", "5"}}) {
    const std::string key = std::string("reftrack ") + order;
    ASSERT_EQ(rows.count(key), 1u) << key << "\n" << r.out;
    ASSERT_EQ(rows.at(key).size(), 10u) << key;
    EXPECT_EQ(rows.at(key)[0], frames) << key;
    EXPECT_NE(r.err.find(std::string("reftrack, ") + order + " order: "), std::string::npos)
        << r.err;
  }
  const std::size_t cuts = r.out.find("reftrack cuts:3: per cut @position frame->frame");
  ASSERT_NE(cuts, std::string::npos) << r.out;
  const std::string cutsLine = r.out.substr(cuts, r.out.find('\n', cuts) - cuts);
  EXPECT_NE(cutsLine.find(": @8 "), std::string::npos) << cutsLine;
  EXPECT_NE(cutsLine.find(", @16 "), std::string::npos) << cutsLine;
  EXPECT_NE(cutsLine.find("; max k="), std::string::npos) << cutsLine;
  const auto csv = dir / "out" / "cube_errors.csv";
  const std::vector<double> sequence = csvColumn(csv, "reftrack_sequence_px");
  const std::vector<double> stride = csvColumn(csv, "reftrack_stride:5_px");
  ASSERT_EQ(sequence.size(), 24u);
  ASSERT_EQ(stride.size(), 24u);
  EXPECT_EQ(csvColumn(csv, "reftrack_shuffled-sequence_px").size(), 24u);
  EXPECT_EQ(csvColumn(csv, "reftrack_cuts:3_px").size(), 24u);
  for (std::size_t k = 0; k < 24; ++k)
    if (k % 5 != 0) {
      EXPECT_TRUE(std::isnan(stride[k])) << k;
    }
}

namespace {

// A folder of `count` noise frames of `size`, a camera file for `cameraSize` and a ground truth
// for frames 0 .. truthFrames-1 (at k / 30 s).
struct SmallRecording {
  std::filesystem::path dir, frames, camera, gt;
  SmallRecording(const std::string& name, cv::Size size, cv::Size cameraSize, int truthFrames) {
    dir = freshTempDir(name);
    frames = dir / "frames";
    std::filesystem::create_directories(frames);
    cv::RNG rng(3);
    for (int k = 0; k < 3; ++k) {
      cv::Mat image(size, CV_8UC3);
      rng.fill(image, cv::RNG::UNIFORM, 0, 255);
      cv::imwrite((frames / ("00000" + std::to_string(k) + ".png")).string(), image);
    }
    Eigen::Matrix3d K;
    K << 200, 0, 0.5 * (cameraSize.width - 1), 0, 200, 0.5 * (cameraSize.height - 1), 0, 0, 1;
    camera = dir / "camera.yml";
    reftrack::PinholeCamera(K, cameraSize).save(camera);
    reftrack::TumTrajectory t;
    for (int k = 0; k < truthFrames; ++k)
      t.poses.push_back({k / 30.0, reftrack::RigidPose(Eigen::Matrix3d::Identity(),
                                                       Eigen::Vector3d(0.01 * k, 0, 1))});
    gt = dir / "groundtruth.txt";
    t.save(gt);
  }
  std::string args(const std::string& refFrames = "0,2") const {
    return "bench-real --input " + frames.string() + " --camera " + camera.string() + " --gt " +
           gt.string() + " --ref-frames " + refFrames + " --out " + (dir / "out").string();
  }
};

}  // namespace

// Bad input: a clear message, a non-zero exit and no output folder.
TEST(BenchRealCommand, InputModeBadInputIsAClearErrorWithNoOutputs) {
  const SmallRecording ok("BenchRealCommandBadInput", {160, 120}, {160, 120}, 3);
  auto expectError = [&](const std::string& args, int exitCode, const std::string& message) {
    const auto r = runReftrack(args, ok.dir);
    EXPECT_EQ(r.exitCode, exitCode) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(ok.dir / "out")) << args;
  };
  std::string args = ok.args();
  expectError(std::string(args).replace(args.find(ok.frames.string()), ok.frames.string().size(),
                                        (ok.dir / "none").string()),
              1, "none' not found");
  expectError(std::string(args).replace(args.find(ok.camera.string()), ok.camera.string().size(),
                                        (ok.dir / "none.yml").string()),
              1, "camera file '" + (ok.dir / "none.yml").string() + "' not found");
  expectError(std::string(args).replace(args.find(ok.gt.string()), ok.gt.string().size(),
                                        (ok.dir / "none.txt").string()),
              1, "ground-truth file '" + (ok.dir / "none.txt").string() + "' not found");
  const SmallRecording shortTruth("BenchRealCommandShortTruth", {160, 120}, {160, 120}, 2);
  expectError(shortTruth.args(), 1, "reference frame 2 has no ground-truth pose");
  EXPECT_FALSE(std::filesystem::exists(shortTruth.dir / "out"));
  const SmallRecording wrongSize("BenchRealCommandWrongSize", {160, 120}, {320, 240}, 3);
  expectError(wrongSize.args(), 1, "is 160x120 but camera file");
  EXPECT_FALSE(std::filesystem::exists(wrongSize.dir / "out"));
  // Usage errors (exit 2), before anything is read.
  expectError(ok.args("3"), 2, "at least two");
  expectError(ok.args("2,2"), 2, "given twice");
  expectError(ok.args() + " --clip card.mp4", 2, "excludes");
  expectError(ok.args() + " --methods reftrack,surf", 2, "unknown method 'surf'");
  expectError(ok.args() + " --order sequence,zigzag", 2, "--order: unknown order 'zigzag'");
  expectError(ok.args() + " --order cuts:1", 2,
              "--order: 'cuts:1': N (the segments) must be a whole number >= 2");
  expectError(ok.args() + " --order stride:0", 2,
              "--order: 'stride:0': K (the stride) must be a whole number >= 1");
  expectError(ok.args() + " --order sequence,sequence", 2, "--order: 'sequence' given twice");
  // Beyond the 3 frames: known once the recording is read, before the map is prepared.
  expectError(ok.args() + " --order cuts:4", 1,
              "--order: 'cuts:4': 4 segments but only 3 frames are benchmarked");
  expectError(ok.args() + " --order sequence,stride:4", 1,
              "--order: 'stride:4': a stride of 4 but only 3 frames are benchmarked");
  expectError("bench-real --input " + ok.frames.string() + " --camera " + ok.camera.string(), 2,
              "--ref-frames");
}

namespace {

// A suite file of 12 frames of the ViSP desk clip (30-41, references 30 and 40, 62 mm apart; the
// suite's cube) and a clip whose folder is absent from the data root.
std::filesystem::path tinySuite(const std::filesystem::path& dir) {
  const auto file = dir / "tiny.yml";
  std::ofstream(file) << "clips:\n"
                         "  - name: visp-12\n"
                         "    folder: visp-desk-apriltags\n"
                         "    first_frame: 30\n"
                         "    last_frame: 41\n"
                         "    references: [30, 40]\n"
                         "    cube: {edge: 0.1, base_centre: [0.18, 0.12, 0]}\n"
                         "    wrong_px: 5\n"
                         "  - name: elsewhere\n"
                         "    folder: no-such-clip\n"
                         "    references: [0, 10]\n"
                         "    cube: {edge: 0.08, in_front_of_reference: {distance: 1.0}}\n"
                         "    wrong_px: 20\n";
  return file;
}

// The suite table's row of (clip, order, method): the 10 fields after them, or none.
std::vector<std::string> suiteRow(const std::string& out, const std::string& clip,
                                  const std::string& order, const std::string& method) {
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream in(line);
    std::vector<std::string> fields;
    for (std::string f; in >> f;) fields.push_back(f);
    if (fields.size() == 13 && fields[0] == clip && fields[1] == order && fields[2] == method)
      return {fields.begin() + 3, fields.end()};
  }
  return {};
}

}  // namespace

// `bench-real --suite` end to end on 12 real frames, reftrack and the SIFT peer, in order and
// shuffled as one sequence: one table with a row per order and method, the skipped clip named,
// progress on stderr, the last line the worst clip's ratio against its best peer, the files under
// --out. A second run with the same --peer-cache takes SIFT's poses from the cache: the same rows
// (ms/frame included, those of the run that filled it). The figures are not bounded here (the
// engine is being changed; the suite is how they are judged).
TEST(BenchRealCommand, SuiteRunsEveryClipIntoOneTable) {
  const auto data = sharedDataDir();
  if (!data || !std::filesystem::is_directory(*data / "visp-desk-apriltags" / "frames"))
    GTEST_SKIP() << "../shared/data/visp-desk-apriltags not available (the shared recordings)";
  const auto dir = freshTempDir("BenchRealCommandSuite");
  const std::string args = "bench-real --suite " + tinySuite(dir).string() + " --data " +
                           data->string() + " --methods reftrack,sift --peer-cache " +
                           (dir / "cache").string();
  const auto r = runReftrack(args + " --out " + (dir / "out").string(), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("skipped clip elsewhere: its folder '"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("skipped: elsewhere: its folder '"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("clip 1 of 1 (visp-12): SIFT+PnP, every frame once (replayed in every "
                       "order): 12 of 12 frames done"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("clip 1 of 1 (visp-12): pass 1/1: reftrack, shuffled-sequence order: 12 "
                       "frames in "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("visp-12: frames 30-41 (12 with a true pose), 640x480; references 30, 40 ("),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("(poses computed)"), std::string::npos) << r.out;
  for (const char* order : {"sequence", "shuffled-sequence"})
    for (const char* method : {"reftrack", "SIFT+PnP"}) {
      const std::vector<std::string> row = suiteRow(r.out, "visp-12", order, method);
      ASSERT_EQ(row.size(), 10u) << order << " " << method << "\n" << r.out;
      EXPECT_EQ(row[0], "12");
      EXPECT_EQ(row[7], "5");  // the clip's wrong_px
    }
  EXPECT_EQ(suiteRow(r.out, "visp-12", "sequence", "SIFT+PnP"),
            suiteRow(r.out, "visp-12", "shuffled-sequence", "SIFT+PnP"));
  const std::string lastLine = "worst clip: visp-12 (";
  const std::size_t last = r.out.rfind(lastLine);
  ASSERT_NE(last, std::string::npos) << r.out;
  EXPECT_NE(r.out.find("): reftrack mean ", last), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" / its best peer SIFT+PnP ", last), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("worst clip in shuffled-sequence order: visp-12"), std::string::npos);
  for (const char* file :
       {"table.txt", "visp-12/table.txt", "visp-12/cube_errors.csv", "visp-12/cube_errors.png"})
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out" / file)) << file;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "elsewhere"));
  EXPECT_EQ(readTextFile(dir / "out" / "table.txt"), r.out.substr(0, r.out.find("wrote the")));

  const auto again = runReftrack(args, dir);
  ASSERT_EQ(again.exitCode, 0) << again.err;
  EXPECT_NE(again.err.find("SIFT+PnP: cached in '" + (dir / "cache").string()), std::string::npos)
      << again.err;
  EXPECT_EQ(again.err.find("frames done"), std::string::npos) << again.err;
  EXPECT_NE(again.out.find("(poses from the cache)"), std::string::npos) << again.out;
  for (const char* order : {"sequence", "shuffled-sequence"})
    EXPECT_EQ(suiteRow(again.out, "visp-12", order, "SIFT+PnP"),
              suiteRow(r.out, "visp-12", order, "SIFT+PnP"))
        << order;
}

// Bad input to --suite: one clear message, exit 1, no output folder; usage errors exit 2.
TEST(BenchRealCommand, SuiteBadInputIsAClearErrorWithNoOutputs) {
  const auto dir = freshTempDir("BenchRealCommandSuiteBad");
  const auto data = dir / "data";
  std::filesystem::create_directories(data / "visp-desk-apriltags");
  const auto suite = tinySuite(dir);
  auto expectError = [&](const std::string& args, int exitCode, const std::string& message) {
    const auto r = runReftrack("bench-real " + args + " --out " + (dir / "out").string(), dir);
    EXPECT_EQ(r.exitCode, exitCode) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << args;
  };
  expectError("--suite " + (dir / "none.yml").string(), 1,
              "suite file '" + (dir / "none.yml").string() + "' not found");
  std::ofstream(dir / "typo.yml") << "clips:\n  - name: a\n    folder: a\n    refs: [0, 4]\n";
  expectError(
      "--suite " + (dir / "typo.yml").string(), 1,
      "suite file '" + (dir / "typo.yml").string() + "': line 4: clips[0].refs: unknown key");
  std::ofstream(dir / "outside.yml")
      << "clips:\n  - name: a\n    folder: a\n    last_frame: 30\n    references: [0, 40]\n"
         "    cube: {edge: 0.1, base_centre: [0, 0, 0]}\n    wrong_px: 5\n";
  expectError("--suite " + (dir / "outside.yml").string(), 1,
              "line 5: clips[0].references[1]: reference frame 40 is outside the clip's frames "
              "0..30");
  expectError("--suite " + suite.string() + " --data " + (dir / "nodata").string(), 1,
              "data folder '" + (dir / "nodata").string() + "' not found");
  expectError(
      "--suite " + suite.string() + " --data " + data.string() + " --clips elsewhere", 1,
      "none of the suite's clips was found in '" + data.string() + "'; elsewhere: its folder '");
  expectError("--suite " + suite.string() + " --data " + data.string() + " --clips visp", 1,
              "has no clip 'visp' (its clips: visp-12, elsewhere)");
  expectError("--suite " + suite.string() + " --data " + data.string(), 1,
              "clip 'visp-12' (suite file '" + suite.string() + "', line 2): its frames '");
  // Usage errors, before anything is read.
  expectError("--suite " + suite.string() + " --input frames", 2, "excludes");
  expectError("--suite " + suite.string() + " --methods reftrack,surf", 2, "unknown method 'surf'");
  expectError("--suite " + suite.string() + " --order sequence,away:3", 2, "--order away:3");
  expectError("--suite " + suite.string() + " --frames 10", 2, "excludes");
  expectError("--peer-cache " + (dir / "cache").string(), 2, "requires --suite");
  expectError("--methods reftrack", 2, "needs --input or --suite");
}
