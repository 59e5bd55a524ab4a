// YamlTree: YAML 1.2 as yaml-cpp reads it, into a flat tree with lines; what reftrack refuses on
// top of the parser (duplicate keys, keys that are not text, cycles, foreign tags, a second
// document, control bytes, deep nesting) is refused with its line.
#include "engine/config/YamlTree.hpp"

#include <gtest/gtest.h>

#include "ErrorMessage.hpp"

using namespace reftrack;
using Kind = YamlTree::Kind;

namespace {

std::string parseError(const std::string& text) {
  return test::errorMessage([&] { parseYamlTree(text); });
}

const YamlTree::Node& valueOf(const YamlTree& tree, const YamlTree::Node& map,
                              const std::string& key) {
  for (const YamlTree::MapEntry& e : map.entries)
    if (e.key == key) return tree.nodes[e.value];
  throw Error("no key " + key);
}

}  // namespace

TEST(YamlTree, ReadsBlockAndFlowStyleWithLinesAndComments) {
  const YamlTree tree = parseYamlTree(
      "# comment\n"
      "a: 1   # after a value\n"
      "b: {x: 2, y: [3, 4]}\n"
      "c:\n"
      "  - \"quoted\"\n"
      "  - plain text\n"
      "  # between items\n"
      "  - |\n"
      "    block\n"
      "d: ~\n"
      "e:\n");
  const YamlTree::Node& root = tree.nodes[0];
  ASSERT_EQ(root.kind, Kind::Map);
  ASSERT_EQ(root.entries.size(), 5u);
  EXPECT_EQ(root.entries[0].key, "a");
  EXPECT_EQ(root.entries[0].line, 2);
  EXPECT_EQ(root.entries[1].line, 3);
  EXPECT_EQ(valueOf(tree, root, "a").text, "1");
  EXPECT_FALSE(valueOf(tree, root, "a").quoted);
  const YamlTree::Node& b = valueOf(tree, root, "b");
  EXPECT_EQ(b.kind, Kind::Map);
  EXPECT_EQ(valueOf(tree, b, "y").items.size(), 2u);
  const YamlTree::Node& c = valueOf(tree, root, "c");
  ASSERT_EQ(c.items.size(), 3u);
  EXPECT_EQ(c.items[0].line, 5);
  EXPECT_TRUE(tree.nodes[c.items[0].value].quoted);
  EXPECT_FALSE(tree.nodes[c.items[1].value].quoted);
  EXPECT_EQ(tree.nodes[c.items[1].value].text, "plain text");
  EXPECT_EQ(tree.nodes[c.items[2].value].text, "block\n");
  EXPECT_EQ(c.items[2].line, 8);
  EXPECT_EQ(valueOf(tree, root, "d").kind, Kind::Null);
  EXPECT_EQ(valueOf(tree, root, "e").kind, Kind::Null);
}

TEST(YamlTree, AnAliasSharesItsAnchorsNodeAndKeepsItsOwnLine) {
  const YamlTree tree = parseYamlTree("base: &w {size: 9}\nother: *w\nlist: [&n 5, *n]\n");
  const YamlTree::Node& root = tree.nodes[0];
  EXPECT_EQ(root.entries[0].value, root.entries[1].value);
  EXPECT_EQ(root.entries[1].line, 2);
  const YamlTree::Node& list = valueOf(tree, root, "list");
  EXPECT_EQ(list.items[0].value, list.items[1].value);
  EXPECT_EQ(tree.nodes[list.items[1].value].text, "5");
}

TEST(YamlTree, AcceptsOpenCvsDirectiveTagAndEscapes) {
  // cv::FileStorage writes `%YAML:1.0` (YAML 1.0's form), `!!opencv-matrix` and \' in strings.
  const YamlTree tree = parseYamlTree(
      "%YAML:1.0\n---\nK: !!opencv-matrix\n   rows: 1\n   cols: 1\n   dt: d\n   data: [ 1. ]\n"
      "s: \"Tom\\'s \\\"mug\\\"\\n2nd line\"\n");
  const YamlTree::Node& root = tree.nodes[0];
  EXPECT_TRUE(valueOf(tree, root, "K").opencvMatrix);
  EXPECT_EQ(root.entries[0].line, 3);
  EXPECT_EQ(valueOf(tree, root, "s").text, "Tom's \"mug\"\n2nd line");
  // YAML's own tags: !!str makes text of a number.
  const YamlTree tagged = parseYamlTree("a: !!str 5\nb: !!int 6\nc: !!null ~\nd: !!map {}\n");
  EXPECT_TRUE(valueOf(tagged, tagged.nodes[0], "a").quoted);
  EXPECT_FALSE(valueOf(tagged, tagged.nodes[0], "b").quoted);
  EXPECT_EQ(valueOf(tagged, tagged.nodes[0], "c").kind, Kind::Null);
}

TEST(YamlTree, AnEmptyDocumentIsANullRoot) {
  for (const std::string text : {"", "# only a comment\n", "%YAML:1.0\n---\n", "\xEF\xBB\xBF"}) {
    const YamlTree tree = parseYamlTree(text);
    ASSERT_EQ(tree.nodes.size(), 1u);
    EXPECT_EQ(tree.nodes[0].kind, Kind::Null);
  }
}

TEST(YamlTree, RefusesWhatReftrackCannotReadWithTheLine) {
  EXPECT_EQ(parseError("a: 1\nb:\n  c: 2\n  c: 3\n"),
            "line 4: b.c is given twice in one map (first on line 3)");
  EXPECT_EQ(parseError("a: 1\n[x, y]: 2\n"), "line 2: a key must be text, not a list or map");
  EXPECT_EQ(parseError("a: 1\n*x : 2\n"), "line 2: the referenced anchor is not defined");
  EXPECT_EQ(parseError("a: &x [1]\n*x : 2\n"),
            "line 2: a key must be text, not empty, a list or a map");
  EXPECT_EQ(parseError("a: &x k\n*x : 2\n"), "(no error)");  // an alias of text is a key
  EXPECT_EQ(parseError("a: &x [1, *x]\n"),
            "line 1: an alias inside the node its anchor names (a cycle)");
  EXPECT_EQ(parseError("a: 1\nb: !foo 2\n"),
            "line 2: the tag !foo is not understood (YAML's own tags and !!opencv-matrix are)");
  EXPECT_EQ(parseError("a: !!opencv-matrix [1]\n"),
            "line 1: the tag !!opencv-matrix does not fit a list");
  EXPECT_EQ(parseError("a: !!null 5\n"),
            "line 1: '5' is tagged !!null but is not empty, ~ or null");
  EXPECT_EQ(parseError("a: 1\n---\nb: 2\n"),
            "line 2: a second YAML document starts here; a file holds one");
  EXPECT_EQ(parseError("a: 1\nb: \x7f\n"), "line 2: control byte 0x7F (is this a text file?)");
  EXPECT_EQ(parseError(std::string("a: 1\0", 5)),
            "line 1: control byte 0x00 (is this a text file?)");
  // yaml-cpp's own messages, at its line.
  EXPECT_EQ(parseError("a: *nothing\n"), "line 1: the referenced anchor is not defined");
  EXPECT_EQ(parseError("a: [1,\n"), "line 2: end of sequence flow not found");
}

TEST(YamlTree, NestingIsBoundedBeforeTheParserRecursesDeep) {
  const std::string deep = std::string(kMaxYamlDepth, '[') + std::string(kMaxYamlDepth, ']');
  EXPECT_EQ(parseError(deep), "(no error)");
  EXPECT_EQ(parseError("[" + deep + "]"),
            "line 1: maps and lists nest deeper than " + std::to_string(kMaxYamlDepth) + " levels");
  // Far deeper than yaml-cpp's own guard (about 1000) and the stack would allow: refused at the
  // 101st level, in flow and in block style.
  const int far = 100000;
  EXPECT_EQ(parseError(std::string(far, '[') + std::string(far, ']')),
            "line 1: maps and lists nest deeper than 100 levels");
  std::string block;
  for (int level = 0; level < 1000; ++level) block += std::string(level, ' ') + "k:\n";
  EXPECT_EQ(parseError(block), "line 101: maps and lists nest deeper than 100 levels");
}
