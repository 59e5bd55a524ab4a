#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "CommandTestSupport.hpp"
#include "TestPaths.hpp"

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

TEST(TrackCommand, AFrameOfAnotherSizeMidStreamKeepsEverythingWrittenBeforeIt) {
  const auto dir = freshTempDir("TrackCommand_size_change");
  const auto sim = runReftrack(
      "simulate --preset static --frames 6 --size 320x240 --out " + (dir / "sim").string(), dir);
  ASSERT_EQ(sim.exitCode, 0) << sim.err;
  // Frame 4 of 6 comes from another camera: 640x480.
  const auto frames = dir / "sim" / "frames";
  cv::Mat big;
  cv::resize(cv::imread((frames / "000004.png").string()), big, cv::Size(640, 480));
  cv::imwrite((frames / "000004.png").string(), big);
  const auto r =
      runReftrack("track --reference " + (dir / "sim" / "reference_a.png").string() + " --input " +
                      frames.string() + " --out-csv " + (dir / "out.csv").string() + " --record " +
                      (dir / "out.mp4").string(),
                  dir);
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_NE(r.err.find("is 640x480"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("outputs written up to frame 3"), std::string::npos) << r.err;
  // The four frames before it are kept: CSV rows and recorded frames.
  std::ifstream in(dir / "out.csv");
  int lines = 0;
  for (std::string l; std::getline(in, l);) ++lines;
  EXPECT_EQ(lines, 1 + 4);
  cv::VideoCapture video((dir / "out.mp4").string());
  ASSERT_TRUE(video.isOpened());
  int decoded = 0;
  for (cv::Mat f; video.read(f);) ++decoded;
  EXPECT_EQ(decoded, 4);
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
