#pragma once
// A CLI11 validator for options whose text a `T::parse(text)` reads (board and marker specs):
// the parse error's message becomes the usage error (exit 2).
#include <CLI/CLI.hpp>
#include <string>

#include "engine/core/Error.hpp"

namespace reftrack::app {

template <class T>
CLI::Validator parsingValidator(const std::string& name) {
  return CLI::Validator(
      [](std::string& text) {
        try {
          T::parse(text);
        } catch (const Error& e) {
          return std::string(e.what());
        }
        return std::string();
      },
      name);
}

}  // namespace reftrack::app
