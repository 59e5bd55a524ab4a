#include "TestPaths.hpp"

namespace reftrack::test {

std::filesystem::path sourceDir() { return REFTRACK_SOURCE_DIR; }

std::filesystem::path freshTempDir(const std::string& name) {
  std::filesystem::path dir = std::filesystem::path(REFTRACK_TEST_TMP_DIR) / name;
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

}  // namespace reftrack::test
