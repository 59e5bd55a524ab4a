#include "engine/config/YamlSubsetValidator.hpp"

#include <cctype>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <vector>

namespace reftrack {

namespace {

// Values nested deeper are refused: reftrack's own files nest four (a map's views: list, item,
// matrix, data); OpenCV's parser recurses once per level.
constexpr int kMaxDepth = 16;
// OpenCV reads a quoted text into a buffer of CV_FS_MAX_LEN (4096) and refuses it when full.
constexpr std::size_t kMaxQuotedLength = 4095;

struct Violation {
  std::size_t row;
  std::string reason;
};

bool isLetter(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }
bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }
bool isAlnum(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; }
// The key characters OpenCV's writer allows (YAMLEmitter::writeScalar).
bool isKeyStart(char c) { return isLetter(c) || c == '_'; }
bool isKeyChar(char c) { return isAlnum(c) || c == '_' || c == '-' || c == ' '; }

std::string quoteForMessage(std::string_view s) {
  constexpr std::size_t kShown = 40;
  std::string quoted(1, '\'');
  quoted.append(s.substr(0, kShown));
  quoted.append(s.size() > kShown ? "...'" : "'");
  return quoted;
}

// Where a value stands: alone on its line (after "key:" or "-" and a line break, or after "- "),
// after "key: " on the key's line, or inside [ ] / { }.
enum class Place { kOwnLine, kAfterKey, kFlow };

class Validator {
 public:
  explicit Validator(std::string_view text) {
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 byte-order mark
    while (!text.empty()) {
      const std::size_t end = text.find('\n');
      std::string_view line = text.substr(0, end);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      lines_.push_back(line);
      if (end == std::string_view::npos) break;
      text.remove_prefix(end + 1);
    }
  }

  void document() {
    checkCharacters();
    if (!lines_.empty() && lines_[0].substr(0, 1) == "%") {
      directive(lines_[0]);
      nextLine();
    }
    skipBlank();
    if (!atEnd() && rest().substr(0, 3) == "---" && col_ == 0) {
      col_ = 3;
      skipSpacesOnLine();
      if (!atLineEnd()) fail("'---' must stand alone on its line");
      skipBlank();
    }
    if (atEnd()) return;
    const char c = peek();
    // OpenCV reads a top-level { } only when it is the last line or follows '---'.
    if (c == '{')
      fail(
          "a top-level { } map (or JSON) is not supported: write 'key: value' lines starting at "
          "column 1");
    if (c == '<') fail("this looks like XML; reftrack reads YAML only ('key: value' lines)");
    if (c == '-' || c == '[') fail("the top level must be a map of 'key: value' lines, not a list");
    if (col_ != 0)
      fail("the top-level keys must start at the beginning of the line (no indentation)");
    // A block map at column 1 takes every later line: it ends only at the end of the text.
    blockMap(0);
    if (!atEnd()) fail("unexpected text after the top-level map");
  }

 private:
  std::vector<std::string_view> lines_;
  std::size_t row_ = 0, col_ = 0;
  int depth_ = 0;

  [[noreturn]] void fail(const std::string& reason) const { throw Violation{row_, reason}; }
  [[noreturn]] void failAt(std::size_t row, const std::string& reason) const {
    throw Violation{row, reason};
  }

  bool atEnd() const { return row_ >= lines_.size(); }
  std::string_view line() const { return lines_[row_]; }
  std::string_view rest() const { return line().substr(std::min(col_, line().size())); }
  // The character `ahead` places on, '\0' at the end of the line.
  char peek(std::size_t ahead = 0) const {
    return col_ + ahead < line().size() ? line()[col_ + ahead] : '\0';
  }
  void nextLine() {
    ++row_;
    col_ = 0;
  }
  void skipSpacesOnLine() {
    while (peek() == ' ') ++col_;
  }
  bool atLineEnd() const { return peek() == '\0' || peek() == '#'; }
  // Past spaces, comments and line ends to the next content (or the end of the text).
  void skipBlank() {
    while (!atEnd()) {
      skipSpacesOnLine();
      if (!atLineEnd()) return;
      nextLine();
    }
  }

  // OpenCV's line reader stops at a NUL, treats a lone CR as a line end and refuses tabs and
  // other control bytes: all are refused up front.
  void checkCharacters() {
    for (row_ = 0; row_ < lines_.size(); ++row_)
      for (const char c : lines_[row_]) {
        if (static_cast<unsigned char>(c) >= 0x20) continue;
        if (c == '\t') fail("a tab character: YAML indents with spaces only");
        if (c == '\r') fail("a carriage return inside the line");
        if (c == '\0') fail("a NUL byte (is this a binary file?)");
        char hex[8];
        std::snprintf(hex, sizeof hex, "0x%02x", static_cast<unsigned>(c));
        fail(std::string("a control character (byte ") + hex + ")");
      }
    row_ = 0;
  }

  void directive(std::string_view text) {
    // "%YAML:1.x" or "%YAML 1.x", which is all OpenCV accepts; it ignores the rest of the line.
    std::size_t i = 0;
    const bool yaml = text.substr(0, 8) == "%YAML:1." || text.substr(0, 8) == "%YAML 1.";
    if (yaml) {
      i = 8;
      while (i < text.size() && isDigit(text[i])) ++i;
      while (i < text.size() && text[i] == ' ') ++i;
    }
    if (!yaml || i == 8 || (i < text.size() && text[i] != '#'))
      fail("the first line may only be the directive %YAML:1.0 (or leave it out)");
  }

  void enter() {
    if (++depth_ > kMaxDepth)
      fail("values nested deeper than " + std::to_string(kMaxDepth) + " levels");
  }

  // The rest of the line after a value on it must be blank or a comment.
  void endOfInlineValue() {
    skipSpacesOnLine();
    if (!atLineEnd()) fail("unexpected text after the value: " + quoteForMessage(rest()));
  }

  void value(int minIndent, Place place) {
    enter();
    const char c = peek(), d = peek(1);
    const bool flow = place == Place::kFlow;
    if (c == '!') {
      tag(minIndent, place);
    } else if (isDigit(c) || ((c == '-' || c == '+') && (isDigit(d) || d == '.')) ||
               (c == '.' && isAlnum(d))) {  // OpenCV's test for a number
      number(flow);
    } else if (c == '"' || c == '\'') {
      quoted(flow);
    } else if (c == '[' || c == '{') {
      // OpenCV: a [ ] or { } continued on later lines is indented one more than its block.
      flowCollection(flow ? minIndent : minIndent + 1);
      if (!flow) endOfInlineValue();
    } else if (c == '-' && !flow) {
      if (place == Place::kAfterKey)
        fail("a '- ' list must start on the line after 'key:', one item per line");
      blockSequence();
    } else {
      plainTextOrBlockMap(place);
    }
    --depth_;
  }

  void tag(int minIndent, Place place) {
    std::size_t end = col_;
    while (end < line().size() && line()[end] != ' ') ++end;
    const std::string_view name = line().substr(col_, end - col_);
    if (name != "!!opencv-matrix" && name != "!!opencv-nd-matrix")
      fail("unsupported type tag " + quoteForMessage(name) +
           " (only !!opencv-matrix and !!opencv-nd-matrix)");
    col_ = end;
    skipSpacesOnLine();
    const std::string needsMap =
        std::string(name) + " must be followed by its fields (rows, cols, dt, data) as a map";
    if (peek() == '{') {
      flowCollection(place == Place::kFlow ? minIndent : minIndent + 1);
      if (place != Place::kFlow) endOfInlineValue();
      return;
    }
    if (!atLineEnd() || place == Place::kFlow) fail(needsMap);
    const std::size_t tagRow = row_;
    skipBlank();
    if (atEnd() || static_cast<int>(col_) < minIndent || !startsKey(rest()))
      failAt(tagRow, needsMap + " on the following, indented lines");
    blockMap(col_);
  }

  // A 'key:' at the start of `s` (as OpenCV decides it: printable characters up to a ':').
  static bool startsKey(std::string_view s) {
    return !s.empty() && isKeyStart(s[0]) && s.find(':') != std::string_view::npos;
  }

  void number(bool flow) {
    std::size_t end = col_;
    while (end < line().size()) {
      const char c = line()[end];
      if (c == ' ' || c == '#' || (flow && (c == ',' || c == ']' || c == '}'))) break;
      ++end;
    }
    const std::string_view token = line().substr(col_, end - col_);
    // OpenCV reads digits after an optional sign; a '.' or 'e' next makes it strtod, else strtol
    // with base 0. The whole token must be that number.
    std::size_t i = token[0] == '-' || token[0] == '+' ? 1 : 0;
    while (i < token.size() && isDigit(token[i])) ++i;
    const std::string copy(token);
    bool whole = false;
    if (i < token.size() && (token[i] == '.' || token[i] == 'e')) {
      const char* first = copy.data() + (copy[0] == '+' ? 1 : 0);
      std::string special(first + (*first == '-' ? 1 : 0));
      for (char& ch : special) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      double parsed = 0;
      const auto [ptr, ec] = std::from_chars(first, copy.data() + copy.size(), parsed);
      whole = (ptr == copy.data() + copy.size() &&
               (ec == std::errc() || ec == std::errc::result_out_of_range)) ||
              special == ".nan" || special == ".inf";  // how OpenCV writes NaN and infinity
    } else {
      char* stop = nullptr;
      const long parsed = std::strtol(copy.c_str(), &stop, 0);
      whole = stop == copy.c_str() + copy.size();
      if (whole && (parsed > 2147483647L || parsed < -2147483647L - 1))
        fail(quoteForMessage(token) +
             " is too large for a whole number (OpenCV's are 32-bit); quote it if it is text");
    }
    if (!whole)
      fail(quoteForMessage(token) + " is not a number; quote text that starts like one (\"" + copy +
           "\")");
    col_ = end;
    if (!flow) endOfInlineValue();
  }

  void quoted(bool flow) {
    const char q = peek();
    std::size_t length = 0;
    for (++col_;; ++col_) {
      const char c = peek();
      if (col_ >= line().size())
        fail("a quoted text must end on the line where it starts (missing " + std::string(1, q) +
             ")");
      if (c == q) {
        if (q == '\'' && peek(1) == '\'') {  // '' is a quote inside '...'
          ++col_;
        } else {
          ++col_;
          break;
        }
      } else if (c == '\\' && q == '"') {
        const char e = peek(1);
        if (e != '"' && e != '\\' && e != '\'' && e != 'n' && e != 'r' && e != 't')
          fail(std::string("unsupported escape '\\") + (e ? std::string(1, e) : "") +
               "' in a quoted text (use \\n, \\t, \\\\ or \\\")");
        ++col_;
      }
      if (++length > kMaxQuotedLength)
        fail("a quoted text longer than " + std::to_string(kMaxQuotedLength) + " characters");
    }
    if (!flow) endOfInlineValue();
  }

  void failOnPlainStart(char c) {
    if (c == '|' || c == '>')
      fail("multi-line text ('|' or '>') is not supported; write it as one quoted line");
    if (c == '&' || c == '*') fail("anchors and aliases ('&', '*') are not supported");
    if (c == '?') fail("complex keys ('?') are not supported");
    if (c == '%') fail("a '%' directive is allowed only as the first line");
    if (c == '\0' || c == '#') fail("a value is missing here");
    fail(std::string("text starting with '") + c + "' must be quoted (\"...\")");
  }

  // Plain text, or (alone on its line or after "- ") a block map whose first key starts here.
  void plainTextOrBlockMap(Place place) {
    const char c = peek();
    const bool flow = place == Place::kFlow;
    const std::string_view indicators = "-?:,[]{}#&*!|>'\"%@`";
    if (indicators.find(c) != std::string_view::npos || c == '\0') failOnPlainStart(c);
    std::size_t end = col_;
    for (; end < line().size(); ++end) {
      const char ch = line()[end];
      if (flow && (ch == ',' || ch == ']' || ch == '}')) break;
      if (ch == '#' && line()[end - 1] == ' ')
        fail(
            "a comment after text is read by OpenCV as part of the text: move the comment to "
            "its own line or quote the text");
      if (ch == ':') {
        if (place == Place::kOwnLine) {
          blockMap(col_);
          return;
        }
        fail("text containing ':' must be quoted (\"...\")" +
             std::string(place == Place::kAfterKey
                             ? "; a nested map goes on the following, indented lines"
                             : ""));
      }
      if (flow && (ch == '[' || ch == '{'))
        fail(std::string("text containing '") + ch + "' inside [ ] or { } must be quoted");
    }
    col_ = end;
  }

  void key(std::map<std::string_view, std::size_t>& seen) {
    const char c = peek();
    if (rest().substr(0, 3) == "---")
      fail("a second document ('---') is not supported: a file holds one map");
    if (rest().substr(0, 3) == "...") fail("'...' (end of document) is not supported");
    if (c == '-') fail("a '- ' list item where a 'key: value' line is expected");
    if (c == '"' || c == '\'') fail("keys are written without quotes");
    if (c == '%') fail("a '%' directive is allowed only as the first line");
    if (!isKeyStart(c)) fail(std::string("a key must start with a letter or '_', not '") + c + "'");
    const std::size_t start = col_;
    while (isKeyChar(peek())) ++col_;
    if (peek() != ':') {
      if (peek() == '\0') fail("expected 'key: value' (no ':' on this line)");
      fail(std::string("a key may hold only letters, digits, '_', '-' and spaces, not '") + peek() +
           "'");
    }
    std::string_view name = line().substr(start, col_ - start);
    while (name.back() == ' ') name.remove_suffix(1);
    const auto [at, added] = seen.emplace(name, row_);
    if (!added)
      fail("the key '" + std::string(name) + "' appears twice in the same map (first on line " +
           std::to_string(at->second + 1) + ")");
    ++col_;  // ':'
  }

  // Block map with its keys at column `indent`; the current position is its first key.
  void blockMap(std::size_t indent) {
    std::map<std::string_view, std::size_t> seen;
    for (;;) {
      const std::size_t keyRow = row_;
      const std::string_view keyText = rest();
      key(seen);
      skipSpacesOnLine();
      if (atLineEnd()) {
        skipBlank();
        if (atEnd() || col_ <= indent) {
          const bool listBelow = !atEnd() && col_ == indent && peek() == '-';
          const std::string keyName(keyText.substr(0, keyText.find(':')));
          failAt(keyRow, listBelow ? "the '- ' items under '" + keyName +
                                         ":' must be indented more than the key"
                                   : "'" + keyName + ":' has no value");
        }
        value(static_cast<int>(indent) + 1, Place::kOwnLine);
      } else {
        value(static_cast<int>(indent) + 1, Place::kAfterKey);
      }
      skipBlank();
      if (atEnd() || col_ < indent) break;
      if (col_ > indent)
        fail("unexpected indentation: expected " + std::to_string(indent) +
             " spaces, like the key on line " + std::to_string(keyRow + 1));
    }
  }

  // Block sequence whose '-' stand at the current column.
  void blockSequence() {
    const std::size_t indent = col_;
    for (;;) {
      if (peek(1) != ' ' && peek(1) != '\0') fail("a list item needs a space after '-'");
      const std::size_t itemRow = row_;
      ++col_;
      skipSpacesOnLine();
      if (atLineEnd()) {
        skipBlank();
        if (atEnd() || col_ <= indent) failAt(itemRow, "the list item '-' has no value");
      }
      value(static_cast<int>(indent) + 1, Place::kOwnLine);
      skipBlank();
      if (atEnd() || col_ < indent) break;
      if (col_ > indent)
        fail("unexpected indentation: expected " + std::to_string(indent) +
             " spaces, like the '-' on line " + std::to_string(itemRow + 1));
      if (rest().substr(0, 3) == "---")
        fail("a second document ('---') is not supported: a file holds one map");
      if (peek() != '-') fail("expected another '- ' list item, or less indentation");
    }
  }

  // [ ] or { } starting at the current position; its later lines start at or after `minIndent`.
  void flowCollection(int minIndent) {
    const char open = peek(), close = open == '[' ? ']' : '}';
    const std::size_t openRow = row_;
    std::map<std::string_view, std::size_t> seen;
    const auto skip = [&] {
      const std::size_t before = row_;
      skipBlank();
      if (atEnd())
        failAt(openRow, std::string("'") + open + "' is never closed with '" + close + "'");
      if (row_ != before && static_cast<int>(col_) < minIndent)
        fail(std::string("a continued ") + open + " " + close + " must be indented by at least " +
             std::to_string(minIndent) + " spaces");
    };
    const auto closes = [&] {
      const char c = peek();
      if (c != ']' && c != '}') return false;
      if (c != close)
        fail(std::string("'") + c + "' where '" + close + "' should close the '" + open +
             "' of line " + std::to_string(openRow + 1));
      ++col_;
      return true;
    };
    ++col_;
    skip();
    if (closes()) return;
    for (;;) {
      if (open == '{') {
        key(seen);
        skip();
      }
      value(minIndent, Place::kFlow);
      skip();
      if (closes()) return;
      if (peek() != ',') fail(std::string("expected ',' or '") + close + "'");
      ++col_;
      skip();
      if (peek() == ']' || peek() == '}') fail("a ',' must be followed by another element");
    }
  }
};

}  // namespace

std::optional<YamlSubsetViolation> findYamlSubsetViolation(std::string_view text) {
  Validator validator(text);
  try {
    validator.document();
  } catch (const Violation& v) {
    return YamlSubsetViolation{static_cast<int>(v.row) + 1, v.reason};
  }
  return std::nullopt;
}

}  // namespace reftrack
