#include "engine/config/KnownKeys.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

std::string dotted(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::vector<std::string> keysOf(const cv::FileNode& map) {
  std::vector<std::string> keys;
  for (const cv::FileNode& child : map) keys.push_back(child.name());
  return keys;
}

[[noreturn]] void throwUnknown(const cv::FileNode& child, const std::string& path,
                               const std::vector<std::string>& known) {
  const std::string key = child.name();
  // A section is a map of keys; an OpenCV matrix (a map with its element type `dt`) is a value.
  const bool section = child.isMap() && child["dt"].empty();
  std::string message = dotted(path, key) + ": unknown " + (section ? "section" : "key") + " — ";
  const std::string nearest = nearestKey(key, known);
  if (nearest.empty())
    message += "this map takes no keys";
  else
    message += "did you mean " + dotted(path, nearest) + "?";
  throw Error(message);
}

void requireKnownTree(const cv::FileNode& node, const std::string& path, const cv::FileNode& known,
                      const std::vector<std::string>& alsoKnown) {
  if (node.empty() || !node.isMap()) return;
  std::vector<std::string> knownKeys = keysOf(known);
  knownKeys.insert(knownKeys.end(), alsoKnown.begin(), alsoKnown.end());
  requireKnownKeys(node, path, knownKeys);
  for (const cv::FileNode& child : node) {
    const cv::FileNode knownChild = known[child.name()];
    if (child.isMap() && !knownChild.empty() && knownChild.isMap())
      requireKnownTree(child, dotted(path, child.name()), knownChild, {});
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

void requireKnownKeys(const cv::FileNode& node, const std::string& path,
                      const std::vector<std::string>& known) {
  if (node.empty() || !node.isMap()) return;
  for (const cv::FileNode& child : node)
    if (std::find(known.begin(), known.end(), child.name()) == known.end())
      throwUnknown(child, path, known);
}

void requireKeysWrittenBy(const cv::FileNode& node, const std::string& path,
                          const std::function<void(cv::FileStorage&)>& writeDefaults,
                          const std::vector<std::string>& alsoKnown) {
  if (node.empty() || !node.isMap()) return;
  cv::FileStorage out(
      ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  writeDefaults(out);
  const cv::FileStorage written(out.releaseAndGetString(),
                                cv::FileStorage::READ | cv::FileStorage::MEMORY);
  requireKnownTree(node, path, written.root(), alsoKnown);
}

}  // namespace reftrack
