#include "engine/config/FieldDescriber.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

namespace reftrack {

namespace {

// Shortest digits that read back to `value`, with ".0" when they would read as an integer.
template <class Float>
std::string shortestText(Float value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  if (ec != std::errc()) return std::to_string(value);
  std::string text(buffer, end);
  const std::size_t e = text.find('e');
  if (e == std::string::npos) {
    if (text.find('.') == std::string::npos) text += ".0";
    return text;
  }
  // 1e-04 -> 1e-4, 1e+05 -> 1e5 (both read as YAML 1.2 numbers)
  std::string exponent = text.substr(e + 1), mantissa = text.substr(0, e + 1);
  if (exponent[0] == '+') exponent.erase(0, 1);
  const std::size_t digits = exponent[0] == '-' ? 1 : 0;
  while (exponent.size() > digits + 1 && exponent[digits] == '0') exponent.erase(digits, 1);
  return mantissa + exponent;
}

}  // namespace

std::string ParamDescription::section() const {
  const std::size_t dot = key.rfind('.');
  return dot == std::string::npos ? std::string() : key.substr(0, dot);
}

std::string ParamDescription::name() const {
  const std::size_t dot = key.rfind('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

std::string yamlValueText(double value) { return shortestText(value); }

std::string yamlValueText(float value) { return shortestText(value); }

std::string yamlValueText(int value) { return std::to_string(value); }

std::string yamlValueText(bool value) { return value ? "true" : "false"; }

std::string yamlValueText(const std::string& value) {
  std::string text = "\"";
  for (const char c : value) {
    if (c == '"' || c == '\\') text += '\\';
    text += c;
  }
  return text + "\"";
}

std::string intervalText(const std::string& lo, const std::string& hi) {
  std::string text = "[";
  text += lo;
  text += ", ";
  text += hi;
  text += "]";
  return text;
}

std::string allowedText(const OddRange& rule) {
  std::string text = "odd in ";
  text += intervalText(std::to_string(rule.lo), std::to_string(rule.hi));
  return text;
}

std::string allowedText(const OffOrRange& rule) {
  std::string text = "0 (off) or ";
  text += intervalText(std::to_string(rule.lo), std::to_string(rule.hi));
  return text;
}

std::string allowedText(const OneOf& rule) {
  std::string text;
  for (const std::string& w : rule.words) text += (text.empty() ? "" : " | ") + w;
  return text;
}

std::string allowedText(const WrittenAsNumber&) { return "1 | 0"; }

}  // namespace reftrack
