#pragma once
// Shared by the libFuzzer targets: the input as a file in a private scratch folder (the loaders
// take paths, as the commands do), and the contract every reader of user input keeps — a bad
// input throws reftrack::Error; anything else escaping (cv::Exception, std::exception) or a crash,
// hang or leak is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "engine/core/Error.hpp"

namespace reftrack::fuzz {

// A folder of this process (tmpfs when there is one), removed at exit.
inline const std::filesystem::path& scratchDir() {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path base = std::filesystem::is_directory("/dev/shm")
                                           ? std::filesystem::path("/dev/shm")
                                           : std::filesystem::temp_directory_path();
    const std::filesystem::path d = base / ("reftrack-fuzz-" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(scratchDir(), ec);
    });
    return d;
  }();
  return dir;
}

inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// Writes the input to scratchDir()/name and returns its path.
inline std::filesystem::path inputFile(const std::string& name, const std::uint8_t* data,
                                       std::size_t size) {
  const std::filesystem::path file = scratchDir() / name;
  std::ofstream(file, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file;
}

// Runs `read`; reftrack::Error is the expected answer to a bad input and is swallowed.
inline void expectOnlyReftrackErrors(const std::function<void()>& read) {
  try {
    read();
  } catch (const reftrack::Error&) {
  }
}

}  // namespace reftrack::fuzz
