#include "engine/config/YamlTree.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include <cstdio>
#include <sstream>
#include <unordered_map>

#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

using Kind = YamlTree::Kind;

[[noreturn]] void failAt(int line, const std::string& reason) {
  throw Error("line " + std::to_string(line) + ": " + reason);
}

int lineOf(const YAML::Mark& mark) { return mark.is_null() ? 0 : mark.line + 1; }

// What a tag says, as yaml-cpp reports it: "?" untagged, "!" a quoted or block scalar (or the
// non-specific tag), "tag:yaml.org,2002:x" for `!!x`.
enum class TagMeaning { None, Text, Number, Boolean, Null, Map, List, OpenCvMatrix, Unknown };

TagMeaning meaningOf(const std::string& tag) {
  if (tag.empty() || tag == "?" || tag == "!") return TagMeaning::None;
  static const std::string yaml = "tag:yaml.org,2002:";
  if (tag.rfind(yaml, 0) != 0) return TagMeaning::Unknown;
  const std::string name = tag.substr(yaml.size());
  if (name == "str") return TagMeaning::Text;
  if (name == "int" || name == "float") return TagMeaning::Number;
  if (name == "bool") return TagMeaning::Boolean;
  if (name == "null") return TagMeaning::Null;
  if (name == "map") return TagMeaning::Map;
  if (name == "seq") return TagMeaning::List;
  if (name == "opencv-matrix") return TagMeaning::OpenCvMatrix;
  return TagMeaning::Unknown;
}

std::string shortTag(const std::string& tag) {
  static const std::string yaml = "tag:yaml.org,2002:";
  return tag.rfind(yaml, 0) == 0 ? "!!" + tag.substr(yaml.size()) : tag;
}

// Builds the tree from yaml-cpp's events, with its own stack (no recursion here).
class TreeBuilder : public YAML::EventHandler {
 public:
  YamlTree tree;

  void OnDocumentStart(const YAML::Mark& mark) override {
    if (++documents_ > 1)
      failAt(lineOf(mark), "a second YAML document starts here; a file holds one");
  }
  void OnDocumentEnd() override {}

  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    const std::uint32_t node = create(Kind::Null, lineOf(mark), anchor);
    add(node, lineOf(mark));
  }

  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    const auto found = anchors_.find(anchor);
    if (found == anchors_.end()) failAt(lineOf(mark), "an alias names no anchor");
    for (const Open& open : stack_)
      if (open.node == found->second)
        failAt(lineOf(mark), "an alias inside the node its anchor names (a cycle)");
    add(found->second, lineOf(mark));
  }

  void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                const std::string& value) override {
    const int line = lineOf(mark);
    const std::uint32_t node = create(Kind::Scalar, line, anchor);
    YamlTree::Node& n = tree.nodes[node];
    n.text = value;
    n.quoted = tag == "!";
    switch (meaningOf(tag)) {
      case TagMeaning::None:
        break;
      case TagMeaning::Text:
        n.quoted = true;
        break;
      case TagMeaning::Number:
      case TagMeaning::Boolean:
        n.quoted = false;  // typed: read as its tag says
        break;
      case TagMeaning::Null:
        if (value != "" && value != "~" && value != "null" && value != "Null" && value != "NULL")
          failAt(line, "'" + value + "' is tagged !!null but is not empty, ~ or null");
        n.kind = Kind::Null;
        break;
      default:
        wrongTag(line, tag, "a single value");
    }
    add(node, line);
  }

  void OnSequenceStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    const TagMeaning meaning = meaningOf(tag);
    if (meaning != TagMeaning::None && meaning != TagMeaning::List)
      wrongTag(lineOf(mark), tag, "a list");
    open(Kind::List, lineOf(mark), anchor);
  }
  void OnSequenceEnd() override { close(); }

  void OnMapStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    const TagMeaning meaning = meaningOf(tag);
    if (meaning != TagMeaning::None && meaning != TagMeaning::Map &&
        meaning != TagMeaning::OpenCvMatrix)
      wrongTag(lineOf(mark), tag, "a map");
    const std::uint32_t node = open(Kind::Map, lineOf(mark), anchor);
    tree.nodes[node].opencvMatrix = meaning == TagMeaning::OpenCvMatrix;
  }
  void OnMapEnd() override { close(); }

  void finish() {
    if (tree.nodes.empty()) tree.nodes.emplace_back();  // an empty document: a null root
  }

 private:
  struct Open {
    std::uint32_t node = 0;
    std::string name;      // dotted, for messages ("" at the root)
    bool haveKey = false;  // a map's key is read, its value comes next
    std::string key;
    int keyLine = 0;
    std::unordered_map<std::string, int> keyLines;  // a map's keys so far
  };

  [[noreturn]] static void wrongTag(int line, const std::string& tag, const std::string& on) {
    if (meaningOf(tag) == TagMeaning::Unknown)
      failAt(line, "the tag " + shortTag(tag) +
                       " is not understood (YAML's own tags and !!opencv-matrix are)");
    failAt(line, "the tag " + shortTag(tag) + " does not fit " + on);
  }

  std::uint32_t create(Kind kind, int line, YAML::anchor_t anchor) {
    // A key must be text: a scalar or null key is handled in add(); a collection is refused
    // here, before its content is read.
    if (!stack_.empty() && kind != Kind::Scalar && kind != Kind::Null) {
      const Open& parent = stack_.back();
      if (tree.nodes[parent.node].kind == Kind::Map && !parent.haveKey)
        failAt(line, "a key must be text, not a list or map");
    }
    const auto node = static_cast<std::uint32_t>(tree.nodes.size());
    YamlTree::Node& n = tree.nodes.emplace_back();
    n.kind = kind;
    n.line = line;
    if (anchor != YAML::NullAnchor) anchors_[anchor] = node;
    return node;
  }

  std::uint32_t open(Kind kind, int line, YAML::anchor_t anchor) {
    if (static_cast<int>(stack_.size()) >= kMaxYamlDepth)
      failAt(line, "maps and lists nest deeper than " + std::to_string(kMaxYamlDepth) + " levels");
    const std::uint32_t node = create(kind, line, anchor);
    std::string name;
    if (!stack_.empty()) name = childName();
    add(node, line);
    Open& opened = stack_.emplace_back();
    opened.node = node;
    opened.name = std::move(name);
    return node;
  }

  void close() { stack_.pop_back(); }

  // The dotted name the next value of the innermost open collection gets.
  std::string childName() const {
    const Open& parent = stack_.back();
    const YamlTree::Node& p = tree.nodes[parent.node];
    if (p.kind == Kind::Map)
      return parent.name.empty() ? parent.key : parent.name + "." + parent.key;
    return parent.name + "[" + std::to_string(p.items.size()) + "]";
  }

  // Places `node` (new, or an alias's) where the parser is: the root, a list's next item, a map's
  // key or the value of its key.
  void add(std::uint32_t node, int line) {
    if (stack_.empty()) return;  // the root: nodes[0], the first created
    Open& parent = stack_.back();
    YamlTree::Node& p = tree.nodes[parent.node];
    if (p.kind == Kind::List) {
      p.items.push_back({line, node});
      return;
    }
    if (!parent.haveKey) {
      const YamlTree::Node& key = tree.nodes[node];
      if (key.kind != Kind::Scalar) failAt(line, "a key must be text, not empty, a list or a map");
      const std::string dotted = parent.name.empty() ? key.text : parent.name + "." + key.text;
      const auto [it, inserted] = parent.keyLines.emplace(key.text, line);
      if (!inserted)
        failAt(line, dotted + " is given twice in one map (first on line " +
                         std::to_string(it->second) + ")");
      parent.haveKey = true;
      parent.key = key.text;
      parent.keyLine = line;
      return;
    }
    p.entries.push_back({parent.key, parent.keyLine, node});
    parent.haveKey = false;
  }

  std::vector<Open> stack_;
  std::unordered_map<YAML::anchor_t, std::uint32_t> anchors_;
  int documents_ = 0;
};

// YAML allows tab, line feed and carriage return among the C0 controls, not the others or DEL.
void refuseControlBytes(std::string_view text) {
  int line = 1;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte == '\n') ++line;
    if ((byte < 0x20 && byte != '\t' && byte != '\n' && byte != '\r') || byte == 0x7F) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", byte);
      failAt(line, std::string("control byte ") + hex + " (is this a text file?)");
    }
  }
}

}  // namespace

YamlTree parseYamlTree(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 byte-order mark
  refuseControlBytes(text);
  std::istringstream in{std::string(text)};
  TreeBuilder builder;
  try {
    YAML::Parser parser(in);
    while (parser.HandleNextDocument(builder)) {
    }
  } catch (const YAML::Exception& e) {
    failAt(lineOf(e.mark), e.msg);
  }
  builder.finish();
  return std::move(builder.tree);
}

}  // namespace reftrack
