#include "engine/config/ConfigValue.hpp"

#include <algorithm>
#include <cmath>

#include "engine/config/ConfigFile.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

// The node for `key`, absent when the key or the whole section is (defaults stay).
YamlNode lookup(const YamlNode& section, const std::string& key) {
  if (section.present() && !section.isNull() && !section.isMap())
    section.fail("parameter section '" + section.name() + "' must be a map of key: value");
  return section[key];
}

[[noreturn]] void mustBe(const YamlNode& n, const std::string& what) {
  n.fail("parameter '" + n.name() + "' must be " + what);
}

}  // namespace

void readConfigValue(const YamlNode& section, const std::string& key, double& value) {
  const YamlNode n = lookup(section, key);
  if (!n.present()) return;
  const std::optional<double> v = n.number();
  if (!v) mustBe(n, "a number");
  if (!std::isfinite(*v)) mustBe(n, "finite (got NaN/inf)");
  value = *v;
}

void readConfigValue(const YamlNode& section, const std::string& key, int& value) {
  const YamlNode n = lookup(section, key);
  if (!n.present()) return;
  const std::optional<int> v = n.integer();
  if (!v) mustBe(n, "an integer");
  value = *v;
}

void readConfigValue(const YamlNode& section, const std::string& key, bool& value) {
  const YamlNode n = lookup(section, key);
  if (!n.present()) return;
  const std::optional<bool> v = n.boolean();
  if (!v) mustBe(n, "true or false");
  value = *v;
}

void readConfigValue(const YamlNode& section, const std::string& key, std::string& value) {
  const YamlNode n = lookup(section, key);
  if (!n.present()) return;
  const std::optional<std::string> v = n.text();
  if (!v) mustBe(n, "text");
  value = *v;
}

void checkWithLines(const YamlNode& root, const std::function<void()>& check) {
  try {
    check();
  } catch (const Error& e) {
    const std::string message = e.what(), prefix = "parameter '";
    const std::size_t start = message.rfind(prefix, 0) == 0 ? prefix.size() : std::string::npos;
    const std::size_t end = start == std::string::npos ? start : message.find('\'', start);
    if (end == std::string::npos) throw;
    YamlNode node = root;
    const std::string name = message.substr(start, end - start);
    for (std::size_t from = 0; from <= name.size() && node.isMap();) {
      const std::size_t dot = std::min(name.find('.', from), name.size());
      node = node[name.substr(from, dot - from)];
      from = dot + 1;
    }
    if (node.present() && node.name() == name) node.fail(message);
    throw;
  }
}

void requireFiniteInRange(const std::string& field, double value, double lo, double hi) {
  if (!std::isfinite(value)) throw Error("parameter '" + field + "' must be finite (got NaN/inf)");
  if (value < lo || value > hi)
    throw Error("parameter '" + field + "' must lie in [" + std::to_string(lo) + ", " +
                std::to_string(hi) + "], got " + std::to_string(value));
}

void requireIntInRange(const std::string& field, int value, int lo, int hi) {
  if (value < lo || value > hi)
    throw Error("parameter '" + field + "' must lie in [" + std::to_string(lo) + ", " +
                std::to_string(hi) + "], got " + std::to_string(value));
}

void readParameterText(const std::string& text, const std::string& what,
                       const std::function<void(const YamlNode& root)>& read) {
  const YamlNode root = readConfigText(text, what);
  try {
    read(root);
  } catch (const Error& e) {
    throw Error(what + ": " + e.what());
  }
}

void readParameterFile(const std::filesystem::path& file,
                       const std::function<void(const YamlNode& root)>& read) {
  const std::string where = "parameter file '" + file.string() + "'";
  if (!std::filesystem::exists(file)) throw Error(where + " does not exist");
  const YamlNode root = readConfigFile(file, where);
  try {
    read(root);
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
}

void writeParameterFile(const std::filesystem::path& file,
                        const std::function<void(cv::FileStorage& fs)>& write) {
  writeFileAtomically(file, [&](const std::filesystem::path& tmp) {
    cv::FileStorage fs(tmp.string(), cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
    if (!fs.isOpened()) throw Error("cannot write parameter file '" + file.string() + "'");
    write(fs);
    fs.release();
  });
}

}  // namespace reftrack
