#pragma once
// Atomic file output: the writer fills a temporary file beside the target, which is renamed
// over the target only when the writer returns normally. An interrupted or failed write never
// leaves a half-written file at the target path.
#include <filesystem>
#include <functional>

namespace reftrack {

void writeFileAtomically(const std::filesystem::path& target,
                         const std::function<void(const std::filesystem::path& tmp)>& writer);

}  // namespace reftrack
