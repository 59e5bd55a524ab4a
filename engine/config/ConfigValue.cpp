#include "engine/config/ConfigValue.hpp"

#include <cmath>

#include "engine/config/ConfigFile.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

std::string fieldName(const std::string& sectionName, const std::string& key) {
  return sectionName.empty() ? key : sectionName + "." + key;
}

// The node for `key`, or an empty node when the key is absent (defaults stay).
cv::FileNode lookup(const cv::FileNode& section, const std::string& sectionName,
                    const std::string& key) {
  if (section.empty() || section.isNone()) return cv::FileNode();
  if (!section.isMap())
    throw Error("parameter section '" + sectionName + "' must be a map of key: value");
  return section[key];
}

}  // namespace

void readConfigValue(const cv::FileNode& section, const std::string& sectionName,
                     const std::string& key, double& value) {
  const cv::FileNode n = lookup(section, sectionName, key);
  if (n.empty()) return;
  if (!n.isReal() && !n.isInt())
    throw Error("parameter '" + fieldName(sectionName, key) + "' must be a number");
  const double v = static_cast<double>(n);
  if (!std::isfinite(v))
    throw Error("parameter '" + fieldName(sectionName, key) + "' must be finite (got NaN/inf)");
  value = v;
}

void readConfigValue(const cv::FileNode& section, const std::string& sectionName,
                     const std::string& key, int& value) {
  const cv::FileNode n = lookup(section, sectionName, key);
  if (n.empty()) return;
  if (!n.isInt()) throw Error("parameter '" + fieldName(sectionName, key) + "' must be an integer");
  value = static_cast<int>(n);
}

void readConfigValue(const cv::FileNode& section, const std::string& sectionName,
                     const std::string& key, bool& value) {
  const cv::FileNode n = lookup(section, sectionName, key);
  if (n.empty()) return;
  // OpenCV's YAML reader stores true/false as the strings "true"/"false"; 0/1 as integers.
  if (n.isInt()) {
    const int v = static_cast<int>(n);
    if (v != 0 && v != 1)
      throw Error("parameter '" + fieldName(sectionName, key) + "' must be true or false");
    value = v == 1;
    return;
  }
  if (n.isString()) {
    const std::string s = static_cast<std::string>(n);
    if (s == "true" || s == "True" || s == "TRUE") {
      value = true;
      return;
    }
    if (s == "false" || s == "False" || s == "FALSE") {
      value = false;
      return;
    }
  }
  throw Error("parameter '" + fieldName(sectionName, key) + "' must be true or false");
}

void readConfigValue(const cv::FileNode& section, const std::string& sectionName,
                     const std::string& key, std::string& value) {
  const cv::FileNode n = lookup(section, sectionName, key);
  if (n.empty()) return;
  if (!n.isString()) throw Error("parameter '" + fieldName(sectionName, key) + "' must be text");
  value = static_cast<std::string>(n);
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

void readParameterFile(const std::filesystem::path& file,
                       const std::function<void(const cv::FileNode& root)>& read) {
  const std::string where = "parameter file '" + file.string() + "'";
  if (!std::filesystem::exists(file)) throw Error(where + " does not exist");
  cv::FileStorage fs = openConfigFile(file, where);
  try {
    read(fs.root());
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  } catch (const cv::Exception& e) {
    throw Error(where + " has a malformed entry: " + e.err);
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
