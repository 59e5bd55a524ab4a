// Ctrl-C / SIGTERM: signals sent to the real `reftrack` process mid-run. Every output must be
// complete up to the last frame handled (MP4 decodable by ffprobe with as many frames as the CSV
// has rows) or absent — never a half-written file, and no temporary file left behind.
#include "app/cli/Interruption.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <thread>
#include <vector>

#include "TestPaths.hpp"
#include "app/commands/CommandTestSupport.hpp"
#include "engine/core/TemporaryOutputs.hpp"
#include "engine/geometry/PinholeCamera.hpp"

namespace reftrack::app {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// Starts `reftrack args...` with stdout/stderr to files in `dir`; returns the child's pid.
pid_t spawnReftrack(const std::vector<std::string>& args, const fs::path& dir) {
  std::vector<std::string> argv{test::reftrackBinary().string()};
  argv.insert(argv.end(), args.begin(), args.end());
  const std::string out = (dir / "stdout.txt").string(), err = (dir / "stderr.txt").string();
  const pid_t pid = fork();
  if (pid == 0) {
    if (!freopen(out.c_str(), "w", stdout) || !freopen(err.c_str(), "w", stderr)) _exit(127);
    std::vector<char*> raw;
    for (std::string& a : argv) raw.push_back(a.data());
    raw.push_back(nullptr);
    execv(raw[0], raw.data());
    _exit(127);
  }
  return pid;
}

// Waits until `ready` holds (polling), at most `limit`; false on time-out or if the child ended.
template <class Ready>
bool waitUntil(pid_t pid, Ready ready, std::chrono::seconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (ready()) return true;
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(20ms);
  }
  return false;
}

int waitExit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 1000 + WTERMSIG(status);
  return -1;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

int lineCount(const fs::path& p) {
  std::ifstream in(p);
  int n = 0;
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#') ++n;
  return n;
}

// Temporary files of unfinished outputs (writeFileAtomically's ".tmp-*", the recorder's
// ".*.recording.mp4/.txt") anywhere under `dir`.
std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(".tmp-", 0) == 0 || name.find(".recording.") != std::string::npos)
      found.push_back(name);
  }
  return found;
}

// A 320x240 clip of random shapes of `frames` frames drifting slowly, its first frame as the
// reference.
void writeClip(const fs::path& dir, int frames) {
  cv::Mat texture(480, 640, CV_8UC3, cv::Scalar::all(128));
  cv::RNG rng(7);
  for (int i = 0; i < 400; ++i) {  // corners and blobs for the keypoint registrar
    const cv::Point p(rng.uniform(0, 640), rng.uniform(0, 480));
    const cv::Scalar colour(rng.uniform(0, 255), rng.uniform(0, 255), rng.uniform(0, 255));
    if (i % 2)
      cv::rectangle(texture, p, p + cv::Point(rng.uniform(5, 40), rng.uniform(5, 40)), colour, -1);
    else
      cv::circle(texture, p, rng.uniform(3, 20), colour, -1);
  }
  cv::VideoWriter writer((dir / "clip.mp4").string(), cv::CAP_FFMPEG,
                         cv::VideoWriter::fourcc('m', 'p', '4', 'v'), 30.0, cv::Size(320, 240));
  ASSERT_TRUE(writer.isOpened());
  for (int k = 0; k < frames; ++k) {
    const cv::Mat frame = texture(cv::Rect(40 + k % 100, 40 + (k / 2) % 100, 320, 240)).clone();
    if (k == 0) cv::imwrite((dir / "reference.png").string(), frame);
    writer.write(frame);
  }
}

TEST(Interruption, TrackFinishesItsRecordingAndCsvUpToTheLastFrameOnSigint) {
  const fs::path dir = test::freshTempDir("Interruption_Track");
  writeClip(dir, 3000);
  const fs::path mp4 = dir / "out.mp4", csv = dir / "frames.csv";
  const pid_t pid = spawnReftrack(
      {"track", "--mode", "homography", "--reference", (dir / "reference.png").string(), "--input",
       (dir / "clip.mp4").string(), "--record", mp4.string(), "--out-csv", csv.string()},
      dir);
  // Interrupt once the recording is under way.
  ASSERT_TRUE(waitUntil(
      pid, [&] { return fs::exists(dir / ".out.recording.mp4"); }, 120s))
      << slurp(dir / "stderr.txt");
  std::this_thread::sleep_for(500ms);
  kill(pid, SIGINT);
  const int exit = waitExit(pid);
  const std::string err = slurp(dir / "stderr.txt");
  ASSERT_EQ(exit, 128 + SIGINT) << err;  // not 0: the 3000-frame clip was cut short
  EXPECT_NE(err.find("interrupted by SIGINT"), std::string::npos) << err;
  // Both outputs complete and in agreement: one CSV row and one video frame per frame handled.
  ASSERT_TRUE(fs::exists(csv));
  ASSERT_TRUE(fs::exists(mp4));
  const int rows = lineCount(csv) - 1;  // minus the header
  EXPECT_GT(rows, 0);
  EXPECT_LT(rows, 3000);
  EXPECT_EQ(test::ffprobeFrameCount(mp4, dir), rows);
  EXPECT_TRUE(leftovers(dir).empty()) << leftovers(dir).front();
}

TEST(Interruption, SimulateOnSigtermLeavesAConsistentShorterSequence) {
  const fs::path dir = test::freshTempDir("Interruption_Simulate");
  const fs::path seq = dir / "seq";
  const pid_t pid = spawnReftrack(
      {"simulate", "--frames", "3000", "--size", "160x120", "--out", seq.string()}, dir);
  ASSERT_TRUE(waitUntil(
      pid, [&] { return fs::exists(seq / "frames" / "000003.png"); }, 180s))
      << slurp(dir / "stderr.txt");
  kill(pid, SIGTERM);
  const int exit = waitExit(pid);
  ASSERT_EQ(exit, 128 + SIGTERM) << slurp(dir / "stderr.txt");
  int pngs = 0;
  for (const auto& e : fs::directory_iterator(seq / "frames"))
    pngs += e.path().extension() == ".png" ? 1 : 0;
  EXPECT_GE(pngs, 4);
  EXPECT_LT(pngs, 3000);
  EXPECT_EQ(lineCount(seq / "groundtruth.txt"), pngs);  // one pose per frame written
  cv::FileStorage scene((seq / "scene.yml").string(), cv::FileStorage::READ);
  EXPECT_EQ(static_cast<int>(scene["frame_count"]), pngs);
  EXPECT_TRUE(leftovers(dir).empty()) << leftovers(dir).front();
}

TEST(Interruption, ASignalOutsideAnInterruptibleLoopRemovesUnfinishedOutputsAndEndsTheProcess) {
  const fs::path dir = test::freshTempDir("Interruption_Die");
  const fs::path tmp = dir / ".tmp-unfinished.yml";
  std::ofstream(tmp) << "half";
  const pid_t pid = fork();
  if (pid == 0) {
    installInterruptHandlers();
    const TemporaryOutput tracked(tmp);
    raise(SIGTERM);
    _exit(0);  // not reached: the signal's default action ends the process
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_FALSE(fs::exists(tmp));
}

TEST(Interruption, InsideAnInterruptibleLoopTheFirstSignalIsOnlyRecorded) {
  const pid_t pid = fork();
  if (pid == 0) {
    installInterruptHandlers();
    {
      const InterruptibleWork work;
      raise(SIGINT);
      if (!interruptRequested() || interruptSignal() != SIGINT) _exit(3);
    }
    _exit(0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

}  // namespace
}  // namespace reftrack::app
