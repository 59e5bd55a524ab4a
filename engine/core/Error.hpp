#pragma once
// reftrack::Error: a runtime failure with one clear, user-facing message (the CLI prints
// it and exits 1). Input validation everywhere throws this, never asserts.
#include <stdexcept>
#include <string>

namespace reftrack {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace reftrack
