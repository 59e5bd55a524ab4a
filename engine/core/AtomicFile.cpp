#include "engine/core/AtomicFile.hpp"

#include <unistd.h>

#include <atomic>
#include <string>

#include "engine/core/Error.hpp"
#include "engine/core/TemporaryOutputs.hpp"

namespace reftrack {

void writeFileAtomically(const std::filesystem::path& target,
                         const std::function<void(const std::filesystem::path& tmp)>& writer) {
  namespace fs = std::filesystem;
  static std::atomic<int> counter{0};
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(dir)) throw Error("output folder '" + dir.string() + "' does not exist");
  // Keep the extension: OpenCV picks formats (YAML, PNG, ...) from it.
  const fs::path tmp = dir / (".tmp-" + std::to_string(::getpid()) + "-" +
                              std::to_string(counter++) + "-" + target.filename().string());
  const TemporaryOutput tracked(tmp);  // removed if a signal ends the process meanwhile
  try {
    writer(tmp);
    if (!fs::exists(tmp)) throw Error("nothing was written to '" + target.string() + "'");
    fs::rename(tmp, target);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

}  // namespace reftrack
