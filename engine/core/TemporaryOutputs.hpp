#pragma once
// TemporaryOutputs: the temporary files of outputs being written (writeFileAtomically, the MP4
// recorder), so that a process ended by a signal can remove them before it dies:
// removeTemporaryOutputs() is async-signal-safe (unlink of fixed buffers only). At most
// kMaxTemporaryOutputs are tracked at once; further ones are simply not tracked.
#include <filesystem>

namespace reftrack {

inline constexpr int kMaxTemporaryOutputs = 64;

// Tracks `path` while alive.
class TemporaryOutput {
 public:
  explicit TemporaryOutput(const std::filesystem::path& path);
  ~TemporaryOutput();
  TemporaryOutput(const TemporaryOutput&) = delete;
  TemporaryOutput& operator=(const TemporaryOutput&) = delete;

 private:
  int slot_ = -1;
};

// Unlinks every tracked temporary file. Async-signal-safe; returns how many were tracked.
int removeTemporaryOutputs() noexcept;

}  // namespace reftrack
