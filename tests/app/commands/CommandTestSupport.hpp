#pragma once
// Runs the built `reftrack` binary for end-to-end command tests: exit code plus captured output.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
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
  auto slurp = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  r.out = slurp(outFile);
  r.err = slurp(errFile);
  return r;
}

}  // namespace reftrack::test
