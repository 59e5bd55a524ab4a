#pragma once
// Runs the built `reftrack` binary for end-to-end command tests: exit code plus captured output;
// counts a recorded video's frames with ffprobe.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "TestPaths.hpp"

namespace reftrack::test {

struct CommandRun {
  int exitCode = -1;
  std::string out, err;
};

inline CommandRun runReftrack(const std::string& args, const std::filesystem::path& scratch) {
  const auto outFile = scratch / "stdout.txt", errFile = scratch / "stderr.txt";
  const std::string cmd =
      reftrackBinary().string() + " " + args + " >" + outFile.string() + " 2>" + errFile.string();
  const int status = std::system(cmd.c_str());
  CommandRun r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readTextFile(outFile);
  r.err = readTextFile(errFile);
  return r;
}

// Frames of a video counted by decoding (ffprobe -count_frames), or -1 when ffprobe fails.
inline int ffprobeFrameCount(const std::filesystem::path& file,
                             const std::filesystem::path& scratch) {
  const std::filesystem::path out = scratch / "ffprobe.txt";
  const std::string cmd =
      "ffprobe -v error -select_streams v:0 -count_frames -show_entries stream=nb_read_frames "
      "-of default=nokey=1:noprint_wrappers=1 '" +
      file.string() + "' >'" + out.string() + "' 2>&1";
  if (std::system(cmd.c_str()) != 0) return -1;
  std::ifstream in(out);
  int n = -1;
  in >> n;
  return n;
}

}  // namespace reftrack::test
