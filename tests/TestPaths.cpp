#include "TestPaths.hpp"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

namespace reftrack::test {

std::filesystem::path sourceDir() { return REFTRACK_SOURCE_DIR; }

std::filesystem::path freshTempDir(const std::string& name) {
  // The process id keeps tests that CTest runs in parallel (one process each) apart, even when
  // they ask for the same name (for example a suite-wide fixture folder).
  std::filesystem::path dir = std::filesystem::path(REFTRACK_TEST_TMP_DIR) /
                              (name + "_" + std::to_string(static_cast<long>(::getpid())));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::optional<std::filesystem::path> sharedDataDir() {
  std::filesystem::path dir = REFTRACK_SHARED_DATA_DIR;
  if (std::filesystem::is_directory(dir)) return std::filesystem::canonical(dir);
  return std::nullopt;
}

std::filesystem::path reftrackBinary() { return REFTRACK_BINARY; }

std::string readTextFile(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace reftrack::test
