#include "engine/config/YamlNode.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "engine/config/YamlTree.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }

// Digits from `i` on; returns how many.
std::size_t skipDigits(const std::string& s, std::size_t& i) {
  const std::size_t start = i;
  while (i < s.size() && isDigit(s[i])) ++i;
  return i - start;
}

// YAML 1.2 core schema's decimal number: [-+]? (.digits | digits(.digits?)?) ([eE][-+]?digits)?
bool isDecimalNumber(const std::string& s) {
  std::size_t i = 0;
  if (i < s.size() && (s[i] == '-' || s[i] == '+')) ++i;
  std::size_t digits = skipDigits(s, i);
  if (i < s.size() && s[i] == '.') {
    ++i;
    digits += skipDigits(s, i);
  }
  if (digits == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '-' || s[i] == '+')) ++i;
    if (skipDigits(s, i) == 0) return false;
  }
  return i == s.size();
}

bool isInteger(const std::string& s) {
  std::size_t i = 0;
  if (i < s.size() && (s[i] == '-' || s[i] == '+')) ++i;
  return skipDigits(s, i) > 0 && i == s.size();
}

}  // namespace

YamlNode::YamlNode(std::shared_ptr<const YamlTree> tree)
    : tree_(std::move(tree)), index_(0), line_(tree_ ? std::max(tree_->nodes[0].line, 1) : 0) {}

YamlNode::YamlNode(std::shared_ptr<const YamlTree> tree, std::uint32_t index, std::string name,
                   std::string key, int line)
    : tree_(std::move(tree)),
      index_(index),
      name_(std::move(name)),
      key_(std::move(key)),
      line_(line) {}

bool YamlNode::isNull() const {
  return present() && tree_->nodes[index_].kind == YamlTree::Kind::Null;
}
bool YamlNode::isScalar() const {
  return present() && tree_->nodes[index_].kind == YamlTree::Kind::Scalar;
}
bool YamlNode::isList() const {
  return present() && tree_->nodes[index_].kind == YamlTree::Kind::List;
}
bool YamlNode::isMap() const {
  return present() && tree_->nodes[index_].kind == YamlTree::Kind::Map;
}
bool YamlNode::isOpenCvMatrix() const { return isMap() && tree_->nodes[index_].opencvMatrix; }

std::string YamlNode::childName(const std::string& key) const {
  return name_.empty() ? key : name_ + "." + key;
}

YamlNode YamlNode::operator[](const std::string& key) const {
  if (isMap()) {
    for (const YamlTree::MapEntry& e : tree_->nodes[index_].entries)
      if (e.key == key) return YamlNode(tree_, e.value, childName(key), key, e.line);
  } else if (present() && !isNull()) {
    fail((name_.empty() ? std::string("the file") : name_) + " must be a map of key: value");
  }
  return YamlNode(nullptr, 0, childName(key), key, line_);
}

std::vector<YamlNode> YamlNode::children() const {
  std::vector<YamlNode> out;
  if (isMap()) {
    for (const YamlTree::MapEntry& e : tree_->nodes[index_].entries)
      out.push_back(YamlNode(tree_, e.value, childName(e.key), e.key, e.line));
  } else if (isList()) {
    for (std::size_t i = 0; i < size(); ++i) out.push_back(item(i));
  }
  return out;
}

std::size_t YamlNode::size() const {
  if (isMap()) return tree_->nodes[index_].entries.size();
  if (isList()) return tree_->nodes[index_].items.size();
  return 0;
}

YamlNode YamlNode::item(std::size_t index) const {
  if (!isList() || index >= size())
    throw Error("YamlNode::item(" + std::to_string(index) + ") outside " + name_);
  const YamlTree::ListItem& it = tree_->nodes[index_].items[index];
  return YamlNode(tree_, it.value, name_ + "[" + std::to_string(index) + "]", "", it.line);
}

std::optional<std::string> YamlNode::text() const {
  if (!isScalar()) return std::nullopt;
  return tree_->nodes[index_].text;
}

std::optional<double> YamlNode::number() const {
  if (!isScalar() || tree_->nodes[index_].quoted) return std::nullopt;
  const std::string& s = tree_->nodes[index_].text;
  if (isDecimalNumber(s)) {
    const std::size_t sign = s[0] == '+' ? 1 : 0;  // from_chars takes '-' only
    double value = 0;
    const auto [end, ec] = std::from_chars(s.data() + sign, s.data() + s.size(), value);
    if (end == s.data() + s.size() && ec == std::errc()) return value;
    // Beyond a double's range: strtod gives the infinity or the zero (or denormal) it rounds to.
    if (ec == std::errc::result_out_of_range) return std::strtod(s.c_str(), nullptr);
    return std::nullopt;
  }
  const std::string unsigned_ = (s[0] == '-' || s[0] == '+') ? s.substr(1) : s;
  if (unsigned_ == ".inf" || unsigned_ == ".Inf" || unsigned_ == ".INF")
    return s[0] == '-' ? -std::numeric_limits<double>::infinity()
                       : std::numeric_limits<double>::infinity();
  if (s == ".nan" || s == ".NaN" || s == ".NAN" || s == ".Nan")
    return std::numeric_limits<double>::quiet_NaN();
  return std::nullopt;
}

std::optional<int> YamlNode::integer() const {
  if (!isScalar() || tree_->nodes[index_].quoted) return std::nullopt;
  const std::string& s = tree_->nodes[index_].text;
  if (!isInteger(s)) return std::nullopt;
  const std::size_t sign = s[0] == '+' ? 1 : 0;
  int value = 0;
  const auto [end, ec] = std::from_chars(s.data() + sign, s.data() + s.size(), value);
  if (end != s.data() + s.size() || ec != std::errc()) return std::nullopt;  // beyond an int
  return value;
}

std::optional<bool> YamlNode::boolean() const {
  if (!isScalar() || tree_->nodes[index_].quoted) return std::nullopt;
  const std::string& s = tree_->nodes[index_].text;
  if (s == "true" || s == "True" || s == "TRUE" || s == "1") return true;
  if (s == "false" || s == "False" || s == "FALSE" || s == "0") return false;
  return std::nullopt;
}

void YamlNode::fail(const std::string& what) const {
  throw Error("line " + std::to_string(line_) + ": " + what);
}

}  // namespace reftrack
