#include "engine/core/TemporaryOutputs.hpp"

#include <unistd.h>

#include <atomic>
#include <cstring>

namespace reftrack {

namespace {

// Fixed storage: a signal handler may read it at any moment, so nothing here allocates.
// A slot is claimed (0 -> 1), filled, then published (1 -> 2); the handler only reads
// published slots.
constexpr std::size_t kPathBytes = 4096;
struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 published
  char path[kPathBytes];
};
Slot slots[kMaxTemporaryOutputs];

}  // namespace

TemporaryOutput::TemporaryOutput(const std::filesystem::path& path) {
  const std::string text = path.string();
  if (text.size() + 1 > kPathBytes) return;
  for (int i = 0; i < kMaxTemporaryOutputs; ++i) {
    int expected = 0;
    if (!slots[i].state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(slots[i].path, text.c_str(), text.size() + 1);
    slots[i].state.store(2);
    slot_ = i;
    return;
  }
}

TemporaryOutput::~TemporaryOutput() {
  if (slot_ >= 0) slots[slot_].state.store(0);
}

int removeTemporaryOutputs() noexcept {
  int removed = 0;
  for (Slot& slot : slots) {
    if (slot.state.load() != 2) continue;
    ::unlink(slot.path);
    ++removed;
  }
  return removed;
}

}  // namespace reftrack
