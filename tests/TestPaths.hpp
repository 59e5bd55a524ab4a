#pragma once
// Paths shared by the test suites: the source tree, a fresh scratch folder per test, the
// optional ../shared/data recordings (tests skip with a message when they are absent); reading a
// written file back.
#include <filesystem>
#include <optional>
#include <string>

namespace reftrack::test {

std::filesystem::path sourceDir();
// An empty folder unique to `name` under the build tree (removed and recreated).
std::filesystem::path freshTempDir(const std::string& name);
// ../shared/data if it exists, otherwise nullopt.
std::optional<std::filesystem::path> sharedDataDir();
// The built `reftrack` executable, for end-to-end command tests.
std::filesystem::path reftrackBinary();
// The whole content of a file ("" when it cannot be read).
std::string readTextFile(const std::filesystem::path& file);

}  // namespace reftrack::test
