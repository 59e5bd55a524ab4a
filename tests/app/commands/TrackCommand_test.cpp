#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "CommandTestSupport.hpp"
#include "DatasetFixtures.hpp"
#include "TestPaths.hpp"
#include "engine/geometry/TumTrajectory.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(TrackCommand, HomographyModeWritesTheCsv) {
  const auto dir = freshTempDir("TrackCommand_homography");
  // The simulator renders the frames; the first one serves as the reference.
  const auto sim = runReftrack(
      "simulate --preset static --frames 5 --size 320x240 --out " + (dir / "sim").string(), dir);
  ASSERT_EQ(sim.exitCode, 0) << sim.err;
  const auto r = runReftrack("track --reference " + (dir / "sim" / "reference_a.png").string() +
                                 " --input " + (dir / "sim" / "frames").string() + " --out-csv " +
                                 (dir / "out.csv").string(),
                             dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("5 frames, 5 tracked"), std::string::npos) << r.out;
  std::ifstream in(dir / "out.csv");
  int lines = 0;
  for (std::string l; std::getline(in, l);) ++lines;
  EXPECT_EQ(lines, 6);
  // With the simulator's camera (enables the rotation-only model).
  const auto calibrated = runReftrack(
      "track --reference " + (dir / "sim" / "reference_a.png").string() + " --camera " +
          (dir / "sim" / "camera.yml").string() + " --input " + (dir / "sim" / "frames").string(),
      dir);
  ASSERT_EQ(calibrated.exitCode, 0) << calibrated.err;
  EXPECT_NE(calibrated.out.find("5 frames, 5 tracked"), std::string::npos) << calibrated.out;
}

// Frame 4 of 6 comes from another camera (640x480 among 320x240 frames). Without --camera an
// image folder may hold frames of any sizes (photos from several cameras): every frame is
// tracked, written to the CSV and recorded (fitted into the first frame's size). With the
// frames' --camera, whose size it is not, the input ends at it and everything written before it
// is kept.
TEST(TrackCommand, AFrameOfAnotherSizeMidStreamIsTrackedOrEndsTheInputWithACamera) {
  const auto dir = freshTempDir("TrackCommand_size_change");
  const auto sim = runReftrack(
      "simulate --preset static --frames 6 --size 320x240 --out " + (dir / "sim").string(), dir);
  ASSERT_EQ(sim.exitCode, 0) << sim.err;
  const auto frames = dir / "sim" / "frames";
  cv::Mat big;
  cv::resize(cv::imread((frames / "000004.png").string()), big, cv::Size(640, 480));
  cv::imwrite((frames / "000004.png").string(), big);
  const auto countLines = [](const std::filesystem::path& csv) {
    std::ifstream in(csv);
    int lines = 0;
    for (std::string l; std::getline(in, l);) ++lines;
    return lines;
  };
  const auto countFrames = [](const std::filesystem::path& mp4) {
    cv::VideoCapture video(mp4.string());
    int decoded = 0;
    for (cv::Mat f; video.read(f);) ++decoded;
    return decoded;
  };
  const std::string track = "track --reference " + (dir / "sim" / "reference_a.png").string() +
                            " --input " + frames.string();

  const auto any = runReftrack(track + " --out-csv " + (dir / "any.csv").string() + " --record " +
                                   (dir / "any.mp4").string(),
                               dir);
  ASSERT_EQ(any.exitCode, 0) << any.err;
  EXPECT_NE(any.out.find("6 frames, 6 tracked"), std::string::npos) << any.out;
  EXPECT_EQ(countLines(dir / "any.csv"), 1 + 6);
  EXPECT_EQ(countFrames(dir / "any.mp4"), 6);

  const auto r =
      runReftrack(track + " --camera " + (dir / "sim" / "camera.yml").string() + " --out-csv " +
                      (dir / "out.csv").string() + " --record " + (dir / "out.mp4").string(),
                  dir);
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_NE(r.err.find("is 640x480"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("outputs written up to frame 3"), std::string::npos) << r.err;
  EXPECT_EQ(countLines(dir / "out.csv"), 1 + 4);
  EXPECT_EQ(countFrames(dir / "out.mp4"), 4);
}

TEST(TrackCommand, AFileSizeLimitFailsTheRecordingClearlyAndKeepsTheCsv) {
  const auto dir = freshTempDir("TrackCommand_full_disk");
  const auto sim = runReftrack(
      "simulate --preset static --frames 30 --size 320x240 --out " + (dir / "sim").string(), dir);
  ASSERT_EQ(sim.exitCode, 0) << sim.err;
  // 64 kB per file (ulimit -f counts 1024-byte blocks in bash): the ~5 kB CSV fits, 30 noisy
  // 320x240 frames of MP4 (~215 kB) do not. SIGXFSZ ignored, so writes fail with EFBIG as on a full
  // disk.
  const std::string cmd =
      "bash -c 'ulimit -f 64; trap \"\" XFSZ; exec " + reftrackBinary().string() +
      " track --reference " + (dir / "sim" / "reference_a.png").string() + " --input " +
      (dir / "sim" / "frames").string() + " --out-csv " + (dir / "out.csv").string() +
      " --record " + (dir / "out.mp4").string() + "' >" + (dir / "stdout.txt").string() + " 2>" +
      (dir / "stderr.txt").string();
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  std::ifstream errFile(dir / "stderr.txt");
  const std::string err(std::istreambuf_iterator<char>(errFile), {});
  EXPECT_NE(err.find("could not be finished"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.mp4"));  // absent, not truncated
  EXPECT_FALSE(std::filesystem::exists(dir / ".out.recording.mp4"));
  std::ifstream in(dir / "out.csv");
  int lines = 0;
  for (std::string l; std::getline(in, l);) ++lines;
  EXPECT_EQ(lines, 1 + 30);  // the CSV is complete
}

TEST(TrackCommand, UsageAndRuntimeErrors) {
  const auto dir = freshTempDir("TrackCommand_errors");
  cv::imwrite((dir / "ref.png").string(), cv::Mat(240, 320, CV_8UC3, cv::Scalar(9, 9, 9)));
  // Neither --reference nor --map: a usage error.
  EXPECT_EQ(runReftrack("track --input " + dir.string(), dir).exitCode, 2);
  // Options of the other mode: usage errors.
  EXPECT_EQ(runReftrack("track --reference " + (dir / "ref.png").string() + " --map " +
                            dir.string() + " --input x",
                        dir)
                .exitCode,
            2);
  EXPECT_EQ(runReftrack("track --mode 6dof --labels " + (dir / "ref.png").string() + " --map " +
                            dir.string() + " --input x",
                        dir)
                .exitCode,
            2);
  EXPECT_EQ(runReftrack("track --mode 6dof --camera " + (dir / "ref.png").string() + " --map " +
                            dir.string() + " --input x",
                        dir)
                .exitCode,
            2);
  EXPECT_EQ(runReftrack("track --reference missing.png --input x", dir).exitCode, 2);
  // The cube options are 6-DOF's; --cube-at takes three numbers.
  for (const char* cube : {"--cube-at 0,0,0", "--cube-edge 0.1", "--cube 0.1"})
    EXPECT_EQ(runReftrack("track --reference " + (dir / "ref.png").string() + " " + cube +
                              " --input " + (dir / "ref.png").string(),
                          dir)
                  .exitCode,
              2)
        << cube;
  EXPECT_EQ(
      runReftrack("track --map " + dir.string() + " --cube-at 0,nan,0 --input x", dir).exitCode, 2);
  EXPECT_EQ(runReftrack("track --map " + dir.string() + " --cube-at 0,0 --input x", dir).exitCode,
            2);
  // A camera file that is not one: a runtime failure naming it.
  const auto badCamera =
      runReftrack("track --reference " + (dir / "ref.png").string() + " --camera " +
                      (dir / "ref.png").string() + " --input " + (dir / "ref.png").string(),
                  dir);
  EXPECT_EQ(badCamera.exitCode, 1);
  EXPECT_NE(badCamera.err.find("ref.png"), std::string::npos) << badCamera.err;
  // A flat reference has no corners: a runtime failure with one message.
  const auto flat = runReftrack(
      "track --reference " + (dir / "ref.png").string() + " --input " + (dir / "ref.png").string(),
      dir);
  EXPECT_EQ(flat.exitCode, 1);
  EXPECT_FALSE(flat.err.empty());
}

namespace {

// A simulated hand-held clip (640x480: at 320x240 the clip's 110 corners leave frames lost) laid
// out as a dataset: its 10 frames, then the two reference views
// (so `prepare --input ... --ref-frames 10,11` finds them), each with its exact pose as ground
// truth, on a dataset clock far from zero.
struct SimulatedRecording {
  std::vector<cv::Mat> images;
  std::vector<RigidPose> poses;  // world->camera
  std::filesystem::path camera;
};

SimulatedRecording simulatedRecording(const std::filesystem::path& dir) {
  const auto sim = runReftrack(
      "simulate --preset handheld --frames 10 --size 640x480 --out " + (dir / "sim").string(), dir);
  EXPECT_EQ(sim.exitCode, 0) << sim.err;
  SimulatedRecording r;
  r.camera = dir / "sim" / "camera.yml";
  const TumTrajectory frames = TumTrajectory::load(dir / "sim" / "groundtruth.txt");
  const TumTrajectory references = TumTrajectory::load(dir / "sim" / "references.txt");
  for (int k = 0; k < 10; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "%06d.png", k);
    r.images.push_back(cv::imread((dir / "sim" / "frames" / name).string()));
    r.poses.push_back(frames.poses[static_cast<std::size_t>(k)].worldToCamera);
  }
  for (int v = 0; v < 2; ++v) {
    r.images.push_back(
        cv::imread((dir / "sim" / ("reference_0" + std::to_string(v) + ".png")).string()));
    r.poses.push_back(references.poses[static_cast<std::size_t>(v)].worldToCamera);
  }
  return r;
}

// The first field of every non-comment line of a file, up to `separator`.
std::vector<std::string> firstFields(const std::filesystem::path& file, char separator) {
  std::ifstream in(file);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const std::size_t end = line.find(separator);
    out.push_back(line.substr(0, end));
  }
  return out;
}

}  // namespace

// tum:DIR end to end: prepare takes its references and their ground-truth poses from the
// sequence, track keeps the rgb.txt timestamps in the trajectory and the CSV, and eval against
// tum:DIR compares them (no alignment needed: the map's world is the ground truth's).
TEST(TrackCommand, TumInputKeepsItsTimestampsFromPrepareToEval) {
  const auto dir = freshTempDir("TrackCommand_tum");
  const SimulatedRecording rec = simulatedRecording(dir);
  const double t0 = 1305031102.175304;
  std::vector<double> times;
  TumTrajectory gt;
  for (std::size_t k = 0; k < rec.images.size(); ++k) {
    times.push_back(t0 + k / 30.0);
    gt.poses.push_back({times.back(), rec.poses[k]});
  }
  test::writeTumSequence(dir / "tum", rec.images, times, gt);
  const std::string tum = "tum:" + (dir / "tum").string();
  const auto prepare =
      runReftrack("prepare --camera " + rec.camera.string() + " --input " + tum +
                      " --ref-frames 10,11 --poses " + tum + " --out " + (dir / "map").string(),
                  dir);
  ASSERT_EQ(prepare.exitCode, 0) << prepare.err << prepare.out;
  EXPECT_NE(prepare.out.find("TUM RGB-D ground truth"), std::string::npos) << prepare.out;
  const auto track = runReftrack("track --map " + (dir / "map").string() + " --input " + tum +
                                     " --frames 10 --trajectory " + (dir / "traj.txt").string() +
                                     " --out-csv " + (dir / "frames.csv").string(),
                                 dir);
  ASSERT_EQ(track.exitCode, 0) << track.err;
  const std::vector<std::string> listed = firstFields(dir / "tum" / "rgb.txt", ' ');
  std::ifstream rows(dir / "frames.csv");
  std::vector<std::string> csvTimes;
  std::string line;
  std::getline(rows, line);  // header
  while (std::getline(rows, line)) csvTimes.push_back(line.substr(line.find(',') + 1, 17));
  ASSERT_EQ(csvTimes.size(), 10u);
  for (std::size_t k = 0; k < 10; ++k) EXPECT_EQ(csvTimes[k], listed[k]) << k;
  // Every trajectory line carries one of the listed timestamps, to the microsecond.
  const std::vector<std::string> stamped = firstFields(dir / "traj.txt", ' ');
  EXPECT_GE(stamped.size(), 8u);
  for (const std::string& s : stamped)
    EXPECT_NE(std::find(listed.begin(), listed.end(), s), listed.end()) << s;
  const auto eval =
      runReftrack("eval --no-plots --gt " + tum + " --est " + (dir / "traj.txt").string(), dir);
  ASSERT_EQ(eval.exitCode, 0) << eval.err;
  EXPECT_NE(eval.out.find("alignment: none"), std::string::npos) << eval.out;
  // 12 frames have ground truth; the 10 tracked clip frames are associated.
  EXPECT_NE(eval.out.find("frames: 12 ground truth"), std::string::npos) << eval.out;
}

// euroc:DIR end to end: the camera comes from sensor.yaml (said on stdout), the ground truth
// from the body poses through T_BS; the estimate lands in the ground truth's world within a few
// millimetres (simulated references with exact poses; 640x480 at ~0.9 m: SixDofTrack_test
// measures up to 2.1 mm with marker-prepared maps).
TEST(TrackCommand, EurocInputBringsItsCameraAndGroundTruth) {
  const auto dir = freshTempDir("TrackCommand_euroc");
  const SimulatedRecording rec = simulatedRecording(dir);
  const long long t0 = 1403636579763555584LL;
  std::vector<long long> ns;
  std::vector<std::pair<long long, RigidPose>> mocap;
  std::vector<cv::Mat> grey;
  for (std::size_t k = 0; k < rec.images.size(); ++k) {
    ns.push_back(t0 + static_cast<long long>(k) * 50000000LL);
    mocap.push_back({ns.back(), rec.poses[k]});
    cv::Mat g;
    cv::cvtColor(rec.images[k], g, cv::COLOR_BGR2GRAY);  // EuRoC cameras are monochrome
    grey.push_back(g);
  }
  const RigidPose tbs(Eigen::Quaterniond(0.71, 0.0, 0.0, 0.70).normalized(),
                      Eigen::Vector3d(-0.02, -0.06, 0.01));
  test::writeEurocSequence(dir / "euroc", grey, ns, PinholeCamera::load(rec.camera), tbs, mocap);
  const std::string euroc = "euroc:" + (dir / "euroc").string();
  const auto prepare = runReftrack("prepare --input " + euroc + " --ref-frames 10,11 --poses " +
                                       euroc + " --out " + (dir / "map").string(),
                                   dir);
  ASSERT_EQ(prepare.exitCode, 0) << prepare.err << prepare.out;
  EXPECT_NE(prepare.out.find("camera: from"), std::string::npos) << prepare.out;
  EXPECT_NE(prepare.out.find("sensor.yaml (no --camera given)"), std::string::npos) << prepare.out;
  const auto track = runReftrack("track --map " + (dir / "map").string() + " --input " + euroc +
                                     " --frames 10 --trajectory " + (dir / "traj.txt").string(),
                                 dir);
  ASSERT_EQ(track.exitCode, 0) << track.err;
  const auto eval = runReftrack(
      "eval --no-plots --json --gt " + euroc + " --est " + (dir / "traj.txt").string(), dir);
  ASSERT_EQ(eval.exitCode, 0) << eval.err;
  const std::size_t ate = eval.out.find("\"ate_translation_mm\"");
  ASSERT_NE(ate, std::string::npos) << eval.out;
  const double rmse = std::stod(eval.out.substr(eval.out.find("\"rmse\": ", ate) + 8));
  EXPECT_LT(rmse, 5.0) << eval.out;
  // All 10 clip frames tracked in a measured run; 8 leaves room for a re-initialisation.
  const std::size_t associated = eval.out.find("\"associated_frames\": ");
  ASSERT_NE(associated, std::string::npos) << eval.out;
  EXPECT_GE(std::stoi(eval.out.substr(associated + 21)), 8) << eval.out;
}

// The desk clip (../shared/data/desk-chessboard; skipped without it), map of frames 0 and 40 as
// its README prepares it: by default the recorded cube stands on the board (its plane z = 0,
// inner corners x 0..0.32 m, y -0.20..0 m) with a 10 cm edge; --cube-at and --cube-edge (alias
// --cube) place it by hand.
TEST(TrackCommand, DeskCubeStandsOnTheBoardUnlessPlacedByHand) {
  const std::optional<std::filesystem::path> data = sharedDataDir();
  if (!data || !std::filesystem::exists(*data / "desk-chessboard/groundtruth.txt"))
    GTEST_SKIP() << "../shared/data/desk-chessboard not found (the shared real recordings)";
  const auto dir = freshTempDir("TrackCommand_desk_cube");
  const std::filesystem::path clip = *data / "desk-chessboard";
  const auto prepare =
      runReftrack("prepare --input " + (clip / "frames").string() + " --camera " +
                      (clip / "camera.yml").string() + " --ref-frames 0,40 --poses " +
                      (clip / "groundtruth.txt").string() + " --out " + (dir / "map").string(),
                  dir);
  ASSERT_EQ(prepare.exitCode, 0) << prepare.err;
  const std::string track = "track --map " + (dir / "map").string() + " --input " +
                            (clip / "frames").string() + " --frames 2 --record " +
                            (dir / "out.mp4").string();
  const auto cubeLine = [](const std::string& out) {
    const std::size_t at = out.find("cube: ");
    return at == std::string::npos ? std::string() : out.substr(at, out.find('\n', at) - at);
  };
  const auto byDefault = runReftrack(track, dir);
  ASSERT_EQ(byDefault.exitCode, 0) << byDefault.err;
  const std::string line = cubeLine(byDefault.out);
  double x = NAN, y = NAN, z = NAN;
  ASSERT_EQ(std::sscanf(line.c_str(),
                        "cube: edge 0.100 m (scaled to the scene), base centre "
                        "(%lf, %lf, %lf) m",
                        &x, &y, &z),
            3)
      << line;
  EXPECT_NE(line.find("on the scene's plane"), std::string::npos) << line;
  // On the board (the plane fit's base is within 2 mm of z = 0: OverlayCompositor_test).
  EXPECT_GT(x, 0.0);
  EXPECT_LT(x, 0.32);
  EXPECT_GT(y, -0.20);
  EXPECT_LT(y, 0.0);
  EXPECT_LT(std::abs(z), 0.002);
  const auto byHand = runReftrack(track + " --cube-at 0.16,-0.10,0 --cube 0.05", dir);
  ASSERT_EQ(byHand.exitCode, 0) << byHand.err;
  EXPECT_EQ(cubeLine(byHand.out),
            "cube: edge 0.050 m, base centre (0.160, -0.100, 0.000) m, up (0.00, 0.00, 1.00)");
  const auto edgeOnly = runReftrack(track + " --cube-edge 0.2", dir);
  ASSERT_EQ(edgeOnly.exitCode, 0) << edgeOnly.err;
  const auto baseOf = [](const std::string& l) {
    const std::size_t at = l.find("base centre");
    return at == std::string::npos ? std::string() : l.substr(at, l.find(" m, up") - at);
  };
  EXPECT_EQ(cubeLine(edgeOnly.out).substr(0, 19), "cube: edge 0.200 m,") << edgeOnly.out;
  EXPECT_EQ(baseOf(cubeLine(edgeOnly.out)), baseOf(line));  // still on the scene
}
