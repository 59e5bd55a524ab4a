#pragma once
// CommentedParamsFile: parameter descriptions (FieldDescriber.hpp) as a YAML parameter file the
// readers accept — each key under its section, preceded by "# <meaning> (<allowed values>)".
#include <filesystem>
#include <string>
#include <vector>

#include "engine/config/FieldDescriber.hpp"

namespace reftrack {

// The YAML text: `heading` (lines, each written as a comment) first, then the keys in their
// order, a dotted key's sections as nested maps. The keys of one section must be consecutive
// (as describeParams gives them).
std::string commentedParamsYaml(const std::vector<ParamDescription>& keys,
                                const std::string& heading);

// Writes that text to `file` atomically (AtomicFile.hpp: never a half-written file); throws
// reftrack::Error "cannot write parameter file '<file>': <why>" when it cannot.
void writeCommentedParamsFile(const std::filesystem::path& file,
                              const std::vector<ParamDescription>& keys,
                              const std::string& heading);

}  // namespace reftrack
