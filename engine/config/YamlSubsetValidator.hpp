#pragma once
// YamlSubsetValidator: decides, before OpenCV's YAML parser sees a text, whether it keeps to the
// YAML subset reftrack's files are written in: an optional `%YAML:1.x` first line, an optional
// `---` line, then ONE top-level map of `key: value` lines starting at column 1. Values are
// numbers, plain or quoted text on one line, `[ ]` / `{ }` collections (which may span lines),
// indented block maps and `- ` lists, and `!!opencv-matrix` maps; `#` comments on their own line or
// after a value. Anything else (tabs, control bytes, a second directive or document, anchors,
// multi-line text, other tags, text after the top-level map...) is refused with the line and what
// is wrong.
//
// Why: OpenCV 4.6's parser (modules/core/src/persistence_yml.cpp, YAMLParser::parse) assumes
// that whatever follows a top-level collection is `---`, `...` or the end: it skips three bytes
// unchecked (`ptr += 3`), which can step over a line's terminating NUL into stale buffer bytes,
// and its directive loop spins forever on a line starting with '-' after the first document.
// In this subset the top-level map ends only at the end of the text (a block map at column 1
// takes every later line: no key may start with '-' or '.', so neither `---` nor `...` can end
// it), so that code is never reached; every other loop of the parser consumes input or throws
// on each turn.
#include <optional>
#include <string>
#include <string_view>

namespace reftrack {

struct YamlSubsetViolation {
  int line = 0;        // 1-based line of `text` where it leaves the subset
  std::string reason;  // what is wrong there, in the words of someone editing the file
};

// The first place where `text` (UTF-8, a byte-order mark allowed) leaves the subset, or nothing
// when the whole text keeps to it.
std::optional<YamlSubsetViolation> findYamlSubsetViolation(std::string_view text);

}  // namespace reftrack
