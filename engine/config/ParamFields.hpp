#pragma once
// ParamFields: one list of a parameter struct's fields serves its YAML writer, its reader (and so
// its known keys, which requireKeysWrittenBy takes from the writer) and its check. Here are the
// definitions of ParamSection (ParamSection.hpp), for the struct's .cpp, which lists its fields
// once, in order:
//   template <class Self, class Field> void Params::fields(Self& p, const Field& field) {
//     field("count", p.count, Range{4, 100000})  // a value (int/double/bool/text), its rule
//         .help("corners per image; more: slower, steadier");  // its one-line meaning
//     field("mode", p.mode, TextForm<Mode>{toString, parseMode});  // an enum as its name
//     field(p.corners);  // a nested section (a ParamSection with its own kSection)
//   }
//   template struct ParamSection<Params>;  // check(), write(), read() walk that list
//   template void Params::fields(const Params&, const FieldDescriber&);  // `reftrack params`
// A rule is any object with check(name, value) throwing reftrack::Error; name is "section.key".
// The meanings and the rules are what `reftrack params` lists (FieldDescriber.hpp).
#include <opencv2/core.hpp>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/config/ConfigValue.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/config/ParamSection.hpp"
#include "engine/config/YamlNode.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

// Rules: how check() checks a value (a field given without one is not checked).
// Within [lo, hi] (a double must also be finite): "parameter 'section.key' must lie in [lo, hi]".
template <class T>
struct Range {
  T lo, hi;
  template <class Value>
  void check(const std::string& name, const Value& value) const {
    static_assert(
        std::is_same_v<Value, T> || (std::is_same_v<Value, float> && std::is_same_v<T, double>),
        "a Range's bounds have the type of its field (double for a float)");
    if constexpr (std::is_floating_point_v<T>)
      requireFiniteInRange(name, value, lo, hi);
    else
      requireIntInRange(name, value, lo, hi);
  }
};
template <class T>
Range(T, T) -> Range<T>;

// An odd integer within [lo, hi] (window sides).
struct OddRange {
  int lo, hi;
  void check(const std::string& name, const int& value) const;
  template <class Value>
  void check(const std::string& name, const Value& value) const = delete;  // int fields only
};

// 0 (off) or an integer within [lo, hi].
struct OffOrRange {
  int lo, hi;
  void check(const std::string& name, const int& value) const;
  template <class Value>
  void check(const std::string& name, const Value& value) const = delete;  // int fields only
};

// An enum field written and read as its name; parse() throws reftrack::Error on a bad name.
template <class Enum>
struct TextForm {
  std::string (*name)(Enum);
  Enum (*parse)(const std::string&);
  void check(const std::string&, const Enum&) const {}
};

// One of the given words: "parameter 'section.key' must be one of a, b, c; got 'x'".
struct OneOf {
  std::vector<std::string> words;
  void check(const std::string& name, const std::string& value) const;
};

struct Unchecked {
  template <class T>
  void check(const std::string&, const T&) const {}
};

// A bool written as 1 / 0 instead of true / false (read either way).
struct WrittenAsNumber : Unchecked {};

// What a visitor's field(key, value, rule) returns, so that fields() gives each key its meaning
// as field(...).help("..."): FieldDescriber keeps it, the visitors here drop it.
struct HelpIgnored {
  void help(const char*) const {}
};

// The visitors fields() is walked with.
class FieldWriter {
 public:
  explicit FieldWriter(cv::FileStorage& fs) : fs_(fs) {}
  template <class T, class Rule = Unchecked>
  HelpIgnored operator()(const char* key, const T& value, const Rule& rule = {}) const {
    if constexpr (std::is_enum_v<T>)
      fs_ << key << rule.name(value);
    else if constexpr (std::is_same_v<T, bool> && std::is_same_v<Rule, WrittenAsNumber>)
      fs_ << key << static_cast<int>(value);
    else if constexpr (std::is_same_v<T, bool>)
      fs_ << key << (value ? "true" : "false");
    else
      fs_ << key << value;
    return {};
  }
  template <class Section>
  void operator()(const Section& section) const {
    fs_ << Section::kSection << "{";
    section.write(fs_);
    fs_ << "}";
  }

 private:
  cv::FileStorage& fs_;
};

class FieldReader {
 public:
  explicit FieldReader(const YamlNode& node) : node_(node) {}
  template <class T, class Rule = Unchecked>
  HelpIgnored operator()(const char* key, T& value, const Rule& rule = {}) const {
    if constexpr (std::is_enum_v<T>) {
      std::string name = rule.name(value);
      readConfigValue(node_, key, name);
      checked(key, [&](const std::string&) { value = rule.parse(name); });
    } else if constexpr (std::is_same_v<T, float>) {  // read as a double
      double number = value;
      readConfigValue(node_, key, number);
      value = static_cast<float>(number);
    } else {
      readConfigValue(node_, key, value);
    }
    checked(key, [&](const std::string& name) { rule.check(name, value); });
    return {};
  }
  template <class Section>
  void operator()(Section& section) const {
    section.read(node_[Section::kSection]);
  }

 private:
  // Runs check(its dotted name in the file) on a value the file gives; an error gets its line.
  template <class Check>
  void checked(const char* key, const Check& check) const {
    const YamlNode n = node_.isMap() ? node_[key] : YamlNode();
    if (!n.present()) return;
    try {
      check(n.name());
    } catch (const Error& e) {
      n.fail(e.what());
    }
  }

  YamlNode node_;
};

class FieldChecker {
 public:
  explicit FieldChecker(std::string section) : section_(std::move(section)) {}
  template <class T, class Rule = Unchecked>
  HelpIgnored operator()(const char* key, const T& value, const Rule& rule = {}) const {
    rule.check(section_.empty() ? key : section_ + "." + key, value);
    return {};
  }
  template <class Section>
  void operator()(const Section& section) const {
    section.check();
  }

 private:
  std::string section_;
};

// Refuses keys the writer does not write (and is not told of in alsoKnown), then reads every
// field present; absent ones keep their value (no check: read() runs check() after it).
template <class Params>
void readFields(Params& params, const YamlNode& node,
                const std::vector<std::string>& alsoKnown = {}) {
  requireKeysWrittenBy(
      node, [](cv::FileStorage& fs) { Params{}.write(fs); }, alsoKnown);
  Params::fields(params, FieldReader(node));
}

template <class Params>
void ParamSection<Params>::check() const {
  Params::fields(static_cast<const Params&>(*this), FieldChecker(Params::kSection));
}

template <class Params>
void ParamSection<Params>::write(cv::FileStorage& fs) const {
  Params::fields(static_cast<const Params&>(*this), FieldWriter(fs));
}

template <class Params>
void ParamSection<Params>::read(const YamlNode& node) {
  readFields(static_cast<Params&>(*this), node);
  check();
}

}  // namespace reftrack
