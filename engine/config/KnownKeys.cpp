#include "engine/config/KnownKeys.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "engine/config/YamlTree.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

std::vector<std::string> keysOf(const YamlNode& map) {
  std::vector<std::string> keys;
  for (const YamlNode& child : map.children()) keys.push_back(child.key());
  return keys;
}

[[noreturn]] void throwUnknown(const YamlNode& child, const std::vector<std::string>& known) {
  const std::string& path = child.name();
  const std::string parent = path.substr(0, path.size() - child.key().size());  // "a.b." or ""
  // A section is a map of keys; an OpenCV matrix is a value.
  const bool section = child.isMap() && !child.isOpenCvMatrix();
  std::string message = path + ": unknown " + (section ? "section" : "key") + " — ";
  const std::string nearest = nearestKey(child.key(), known);
  if (child.key() == "<<")
    message +=
        "'<<' merges maps in YAML 1.1 only; write the keys out (an alias may stand for a "
        "whole section)";
  else if (nearest.empty())
    message += "this map takes no keys";
  else
    message += "did you mean " + parent + nearest + "?";
  child.fail(message);
}

void requireKnownTree(const YamlNode& node, const YamlNode& known,
                      const std::vector<std::string>& alsoKnown) {
  if (!node.isMap()) return;
  std::vector<std::string> knownKeys = keysOf(known);
  knownKeys.insert(knownKeys.end(), alsoKnown.begin(), alsoKnown.end());
  requireKnownKeys(node, knownKeys);
  for (const YamlNode& child : node.children()) {
    const YamlNode knownChild = known[child.key()];
    if (child.isMap() && knownChild.isMap()) requireKnownTree(child, knownChild, {});
  }
}

}  // namespace

std::size_t editDistance(std::string_view a, std::string_view b) {
  // One row of the dynamic-programming table at a time.
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::string nearestKey(std::string_view key, const std::vector<std::string>& candidates) {
  // Edit distance less the longer common prefix or suffix, so a shortened or lengthened key
  // finds its full name (source_x -> source_trajectory, not the closer-by-edits "order").
  const auto score = [&](std::string_view c) {
    std::size_t prefix = 0, suffix = 0;
    while (prefix < key.size() && prefix < c.size() && key[prefix] == c[prefix]) ++prefix;
    while (suffix < key.size() && suffix < c.size() &&
           key[key.size() - 1 - suffix] == c[c.size() - 1 - suffix])
      ++suffix;
    return static_cast<long>(editDistance(key, c)) - static_cast<long>(std::max(prefix, suffix));
  };
  std::string best;
  long bestScore = std::numeric_limits<long>::max();
  for (const std::string& c : candidates) {
    const long s = score(c);
    if (s < bestScore) {
      best = c;
      bestScore = s;
    }
  }
  return best;
}

void requireKnownKeys(const YamlNode& node, const std::vector<std::string>& known) {
  if (!node.isMap()) return;
  for (const YamlNode& child : node.children())
    if (std::find(known.begin(), known.end(), child.key()) == known.end())
      throwUnknown(child, known);
}

void requireKeysWrittenBy(const YamlNode& node,
                          const std::function<void(cv::FileStorage&)>& writeDefaults,
                          const std::vector<std::string>& alsoKnown) {
  if (!node.isMap()) return;
  cv::FileStorage out(
      ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  writeDefaults(out);
  const YamlNode written(
      std::make_shared<const YamlTree>(parseYamlTree(out.releaseAndGetString())));
  requireKnownTree(node, written, alsoKnown);
}

}  // namespace reftrack
