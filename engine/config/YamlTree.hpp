#pragma once
// YamlTree: one YAML 1.2 document, parsed by yaml-cpp, as a flat tree of maps, lists, scalars and
// nulls, each with the 1-based line it starts on, for YamlNode to read. Flow and block style,
// comments, anchors and aliases (an alias shares its anchor's node), YAML's own tags and OpenCV's
// `!!opencv-matrix` are read; a `%YAML:1.0` line as OpenCV writes it is accepted. Refused, with
// the line: a syntax error, a control byte, a key given twice in one map, a key that is not text,
// an alias inside the node it names, any other tag, a second document, nesting deeper than
// kMaxYamlDepth.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace reftrack {

inline constexpr int kMaxYamlDepth = 100;  // maps and lists within each other

struct YamlTree {
  enum class Kind : std::uint8_t { Null, Scalar, List, Map };
  struct MapEntry {
    std::string key;
    int line = 0;  // of the key
    std::uint32_t value = 0;
  };
  struct ListItem {
    int line = 0;  // where the item (or the alias standing for it) is written
    std::uint32_t value = 0;
  };
  struct Node {
    Kind kind = Kind::Null;
    bool quoted = false;        // a scalar in quotes, block style or tagged !!str: text only
    bool opencvMatrix = false;  // a map tagged !!opencv-matrix
    int line = 0;
    std::string text;               // a scalar's
    std::vector<MapEntry> entries;  // a map's, in file order
    std::vector<ListItem> items;    // a list's
  };
  std::vector<Node> nodes;  // nodes[0]: the root (Null for an empty document)
};

// Throws reftrack::Error "line N: <what is wrong>" (N 1-based) when `text` is not one such
// document. A UTF-8 byte-order mark in front is skipped.
YamlTree parseYamlTree(std::string_view text);

}  // namespace reftrack
