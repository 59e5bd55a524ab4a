#pragma once
// The message of the reftrack::Error a call throws, for tests of bad input.
#include <functional>
#include <string>

#include "engine/core/Error.hpp"

namespace reftrack::test {

// e.what() of the reftrack::Error `call` throws, or "(no error)" when it throws none.
inline std::string errorMessage(const std::function<void()>& call) {
  try {
    call();
  } catch (const reftrack::Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace reftrack::test
