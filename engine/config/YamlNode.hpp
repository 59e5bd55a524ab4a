#pragma once
// YamlNode: one node of a user's YAML file (read by ConfigFile.hpp) — a map, a list, a single
// value, null, or absent (a key the file leaves out) — with its dotted name ("ransac.seed",
// "views[2].T") and the line it is written on, so that a reader's error says where. The typed
// reads follow YAML 1.2's core schema: a number or a boolean is written plain, never in quotes.
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace reftrack {

struct YamlTree;

class YamlNode {
 public:
  YamlNode() = default;  // absent, unnamed
  // The root of a parsed document, named "" (line 1 when the document is empty).
  explicit YamlNode(std::shared_ptr<const YamlTree> tree);

  bool present() const { return tree_ != nullptr; }
  bool isNull() const;    // written without a value (`key:`), `~` or `null`
  bool isScalar() const;  // a single value: text, a number, a boolean
  bool isList() const;
  bool isMap() const;
  bool isOpenCvMatrix() const;  // a map tagged !!opencv-matrix (YamlMatrix.hpp reads it)

  const std::string& name() const { return name_; }
  int line() const { return line_; }  // 1-based: of its key in a map, of itself in a list

  // A map's value for `key`, named name.key: absent (at this node's line) when this node is
  // absent, null or lacks the key. Throws "line N: <name> must be a map of key: value" when this
  // node is a value or a list.
  YamlNode operator[](const std::string& key) const;
  const std::string& key() const { return key_; }  // its key, when it is a map's value
  // A map's values (with key()) or a list's items (named name[i]) in file order; none otherwise.
  std::vector<YamlNode> children() const;
  std::size_t size() const;                // how many children()
  YamlNode item(std::size_t index) const;  // a list's item; throws unless index < size()

  // A single value as written (quoted or not); nothing for a null, list or map.
  std::optional<std::string> text() const;
  // A plain number: [-+]digits[.digits][e[-+]digits], or .inf, -.inf, .nan in YAML's spellings
  // and OpenCV's (.Inf, .Nan); nothing otherwise.
  std::optional<double> number() const;
  // A plain integer within int's range: [-+]digits; nothing otherwise (2.0 too).
  std::optional<int> integer() const;
  // Plain true/True/TRUE/false/False/FALSE, or 1/0; nothing otherwise.
  std::optional<bool> boolean() const;

  // Throws reftrack::Error "line N: <what>".
  [[noreturn]] void fail(const std::string& what) const;

 private:
  YamlNode(std::shared_ptr<const YamlTree> tree, std::uint32_t index, std::string name,
           std::string key, int line);
  std::string childName(const std::string& key) const;

  std::shared_ptr<const YamlTree> tree_;  // null: absent
  std::uint32_t index_ = 0;
  std::string name_, key_;
  int line_ = 0;
};

}  // namespace reftrack
