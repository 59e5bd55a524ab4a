#pragma once
// KnownKeys: strict configuration. Every key of a map in a user-written YAML file must be one its
// reader knows; an unknown key or section is a reftrack::Error naming its line, itself and the
// nearest known key by edit distance ("line 3: ransac.iterations: unknown key — did you mean
// ransac.max_iterations?"), so a misspelling never passes in silence with the default in its place.
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "engine/config/YamlNode.hpp"

namespace reftrack {

// Levenshtein distance: insertions, deletions and substitutions of one byte each cost 1.
std::size_t editDistance(std::string_view a, std::string_view b);

// The candidate nearest to `key`: the smallest editDistance less the longer common prefix or
// suffix (the first of equals); "" when none is given.
std::string nearestKey(std::string_view key, const std::vector<std::string>& candidates);

// Throws reftrack::Error when the map `node` has a key outside `known`, named by its dotted name
// (node.name() + "." + key). A node that is absent or not a map is left to the reader (it reports
// the missing or mistyped section itself).
void requireKnownKeys(const YamlNode& node, const std::vector<std::string>& known);

// The same check against the keys `writeDefaults` writes (the parameter struct's own writer, so
// reader and writer cannot disagree), into every nested map it writes; `alsoKnown`: top-level
// keys of the same file that other readers handle.
void requireKeysWrittenBy(const YamlNode& node,
                          const std::function<void(cv::FileStorage&)>& writeDefaults,
                          const std::vector<std::string>& alsoKnown = {});

}  // namespace reftrack
