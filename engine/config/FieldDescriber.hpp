#pragma once
// FieldDescriber: walks a parameter struct's one list of fields (ParamFields.hpp) to describe each
// YAML key — its dotted name, its value as YAML, the values its rule allows and the one-line
// meaning fields() gives it with .help("...") — for `reftrack params` and the file it writes.
#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/config/ParamFields.hpp"

namespace reftrack {

struct ParamDescription {
  std::string key;      // dotted: "corners.count"; "mode" at the file's root
  std::string value;    // as YAML, read back to the same value: 55, 0.01, true, "6dof"
  std::string allowed;  // "[4, 100000]", "odd in [3, 31]", "6dof | homography", "true | false"
  std::string help;     // the one-line meaning ("" when fields() gives none)

  std::string section() const;  // the key up to its last dot ("" at the root)
  std::string name() const;     // the key after its last dot
};

// A value as YAML text the parameter readers read back to the same value (a double's shortest
// round-trip digits, with ".0" when they look like an integer; text in double quotes).
std::string yamlValueText(double value);
std::string yamlValueText(float value);
std::string yamlValueText(int value);
std::string yamlValueText(bool value);
std::string yamlValueText(const std::string& value);

// What a rule allows, as `reftrack params` shows it. A rule of another kind shows what its
// describe() returns, or nothing.
std::string intervalText(const std::string& lo, const std::string& hi);  // "[lo, hi]"
template <class T>
std::string allowedText(const Range<T>& rule) {
  return intervalText(yamlValueText(rule.lo), yamlValueText(rule.hi));
}
std::string allowedText(const OddRange& rule);    // "odd in [lo, hi]"
std::string allowedText(const OffOrRange& rule);  // "0 (off) or [lo, hi]"
std::string allowedText(const OneOf& rule);       // "a | b | c"
std::string allowedText(const WrittenAsNumber&);  // "1 | 0"
// The names name() gives the enumerators 0, 1, ... that parse() reads back: "6dof | homography".
template <class Enum>
std::string allowedText(const TextForm<Enum>& rule) {
  std::string text;
  for (int i = 0; i < 64; ++i) {
    const auto value = static_cast<Enum>(i);
    const std::string name = rule.name(value);
    try {
      if (rule.parse(name) == value) text += (text.empty() ? "" : " | ") + name;
    } catch (const Error&) {  // a name parse() refuses is not listed
    }
  }
  return text;
}
template <class Rule>
std::string allowedText(const Rule& rule) {
  if constexpr (requires { rule.describe(); })
    return rule.describe();
  else
    return "";
}

class FieldDescriber {
 public:
  // Appends to `out`; `section` ("" at the file's root) prefixes each key.
  FieldDescriber(std::string section, std::vector<ParamDescription>& out)
      : section_(std::move(section)), out_(out) {}

  // Sets the meaning of the key just described.
  class Help {
   public:
    Help(std::vector<ParamDescription>& out, std::size_t index) : out_(out), index_(index) {}
    void help(const char* text) const { out_[index_].help = text; }

   private:
    std::vector<ParamDescription>& out_;
    std::size_t index_;
  };

  template <class T, class Rule = Unchecked>
  Help operator()(const char* key, const T& value, const Rule& rule = {}) const {
    ParamDescription d;
    d.key = section_.empty() ? key : section_ + "." + key;
    d.allowed = allowedText(rule);
    if constexpr (std::is_enum_v<T>)
      d.value = yamlValueText(rule.name(value));
    else if constexpr (std::is_same_v<T, bool> && std::is_same_v<Rule, WrittenAsNumber>)
      d.value = yamlValueText(static_cast<int>(value));
    else
      d.value = yamlValueText(value);
    if (d.allowed.empty()) d.allowed = allowedOfType<T>();
    out_.push_back(std::move(d));
    return Help(out_, out_.size() - 1);
  }
  template <class Section>
  void operator()(const Section& section) const {
    const std::string name = Section::kSection;
    Section::fields(section, FieldDescriber(section_.empty() ? name : section_ + "." + name, out_));
  }

 private:
  template <class T>
  static std::string allowedOfType() {
    if constexpr (std::is_same_v<T, bool>)
      return "true | false";
    else if constexpr (std::is_same_v<T, std::string>)
      return "text";
    else if constexpr (std::is_integral_v<T>)
      return "integer";
    else
      return "number";
  }

  std::string section_;
  std::vector<ParamDescription>& out_;
};

// Every key of `params` with its value, in the order of its fields(), nested sections in place.
// A struct's fields() is instantiated for FieldDescriber in its .cpp (ParamFields.hpp).
template <class Params>
std::vector<ParamDescription> describeParams(const Params& params = Params{}) {
  std::vector<ParamDescription> out;
  Params::fields(params, FieldDescriber(Params::kSection, out));
  return out;
}

}  // namespace reftrack
