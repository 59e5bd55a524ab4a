#include "engine/config/ConfigFile.hpp"

#include <cctype>
#include <fstream>
#include <iterator>
#include <utility>
#include <vector>

#include "engine/config/YamlSubsetValidator.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

// Values an OpenCV matrix type string holds per element: "d" 1, "3f" 3; 0 when it is not that
// form or has more channels than OpenCV allows (CV_CN_MAX).
long long channelsOf(const std::string& dt) {
  std::size_t digits = 0;
  while (digits < dt.size() && std::isdigit(static_cast<unsigned char>(dt[digits]))) ++digits;
  if (digits + 1 != dt.size() || std::string("ucwsifdh").find(dt.back()) == std::string::npos)
    return 0;
  if (digits == 0) return 1;
  if (digits > 3) return 0;
  const long long channels = std::stoll(dt.substr(0, digits));
  return channels >= 1 && channels <= CV_CN_MAX ? channels : 0;
}

// An OpenCV matrix whose header (rows, cols or sizes, dt) disagrees with its data is refused
// here: OpenCV allocates what the header says before it compares, so "rows: 2000000000" would
// otherwise cost gigabytes or abort on a file of a few bytes.
void checkMatrix(const cv::FileNode& node, const std::string& path, const std::string& what) {
  const cv::FileNode dt = node["dt"], rows = node["rows"], cols = node["cols"],
                     sizes = node["sizes"], data = node["data"];
  const auto bad = [&](const std::string& why) {
    throw Error(what + ": " + (path.empty() ? std::string("the file") : path) +
                " is not a valid matrix: " + why);
  };
  const long long channels = dt.isString() ? channelsOf(static_cast<std::string>(dt)) : 0;
  if (channels == 0) bad("'dt' must be an element type such as d or 3f");
  long long count = channels;
  const auto multiply = [&](const cv::FileNode& n, const char* name) {
    if (!n.isInt() || static_cast<int>(n) < 0) bad(std::string("'") + name + "' must be a count");
    const long long factor = static_cast<int>(n);
    if (factor > 0 && count > (1LL << 40) / factor) bad("it is too large");
    count *= factor;
  };
  if (!sizes.empty()) {
    if (!sizes.isSeq()) bad("'sizes' must be a list of counts");
    for (const cv::FileNode& s : sizes) multiply(s, "sizes");
  } else {
    multiply(rows, "rows");
    multiply(cols, "cols");
  }
  const long long given =
      data.isSeq() ? static_cast<long long>(data.size()) : (data.empty() || data.isNone() ? 0 : 1);
  if (given != count)
    bad("its header asks for " + std::to_string(count) + " values but 'data' holds " +
        std::to_string(given));
}

// Walks the parsed tree (iteratively: the depth is the file's) and checks every matrix.
void checkMatrices(const cv::FileNode& root, const std::string& what) {
  std::vector<std::pair<cv::FileNode, std::string>> pending{{root, ""}};
  while (!pending.empty()) {
    const auto [node, path] = pending.back();
    pending.pop_back();
    if (node.isMap()) {
      if (!node["dt"].empty() && (!node["rows"].empty() || !node["sizes"].empty())) {
        checkMatrix(node, path, what);
        continue;
      }
      for (const cv::FileNode& child : node)
        if (child.isMap() || child.isSeq())
          pending.emplace_back(child, path.empty() ? child.name() : path + "." + child.name());
    } else if (node.isSeq()) {
      for (std::size_t i = 0; i < node.size(); ++i) {
        const cv::FileNode child = node[static_cast<int>(i)];
        if (child.isMap() || child.isSeq())
          pending.emplace_back(child, path + "[" + std::to_string(i) + "]");
      }
    }
  }
}

}  // namespace

std::string withYamlDirective(const std::string& text) {
  const std::size_t start = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;  // UTF-8 byte-order mark
  if (text.compare(start, 1, "%") == 0) return text.substr(start);
  return "%YAML:1.0\n" + text.substr(start);
}

cv::FileStorage openConfigText(const std::string& text, const std::string& what,
                               const std::string& invalid) {
  // OpenCV 4.6's YAML parser never returns on some malformed texts (found by tests/fuzz); the
  // text must keep to the subset YamlSubsetValidator.hpp describes, which excludes them.
  if (const auto violation = findYamlSubsetViolation(text))
    throw Error(what + " " + invalid + ": line " + std::to_string(violation->line) + ": " +
                violation->reason);
  cv::FileStorage fs;
  try {
    if (!fs.open(withYamlDirective(text),
                 cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML))
      throw Error(what + " " + invalid);
  } catch (const cv::Exception& e) {
    throw Error(what + " " + invalid + ": " + e.err);
  } catch (const std::exception& e) {
    // OpenCV 4.6's YAML parser let std::length_error out on a long malformed type tag
    // ("!!opencv-ma\xcc\xcc...", found by tests/fuzz; refused by the validator now).
    throw Error(what + " " + invalid + " (" + e.what() + ")");
  }
  // Every reader looks keys up from the root, which OpenCV asserts is a map.
  const cv::FileNode root = fs.root();
  if (!root.empty() && !root.isNone() && !root.isMap())
    throw Error(what + " must hold a map of key: value at the top level");
  checkMatrices(root, what);
  return fs;
}

cv::FileStorage openConfigFile(const std::filesystem::path& file, const std::string& what,
                               const std::string& invalid) {
  if (std::filesystem::is_directory(file)) throw Error(what + " is a folder, not a file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(what + " cannot be read");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw Error(what + " cannot be read");
  return openConfigText(text, what, invalid);
}

}  // namespace reftrack
