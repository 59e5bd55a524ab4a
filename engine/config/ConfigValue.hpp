#pragma once
// Typed reading of one key of a parameter section (cv::FileNode map). A missing key leaves the
// value unchanged (the default); a value of the wrong type, NaN or infinity throws
// reftrack::Error naming "section.key".
#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <string>

namespace reftrack {

void readConfigValue(const cv::FileNode& section, const std::string& sectionName,
                     const std::string& key, double& value);
void readConfigValue(const cv::FileNode& section, const std::string& sectionName,
                     const std::string& key, int& value);
void readConfigValue(const cv::FileNode& section, const std::string& sectionName,
                     const std::string& key, bool& value);
void readConfigValue(const cv::FileNode& section, const std::string& sectionName,
                     const std::string& key, std::string& value);

// Opens a YAML parameter file (openConfigFile) (the `%YAML:1.0` line may be left out) and hands its
// root to `read`; every failure (missing, unparsable, an unknown or bad entry) throws
// reftrack::Error naming the file.
void readParameterFile(const std::filesystem::path& file,
                       const std::function<void(const cv::FileNode& root)>& read);
// Writes a YAML parameter file atomically (temp file + rename): `write` fills its root map.
void writeParameterFile(const std::filesystem::path& file,
                        const std::function<void(cv::FileStorage& fs)>& write);

// Throws reftrack::Error "<field> must be ..." unless value is finite and within [lo, hi].
void requireFiniteInRange(const std::string& field, double value, double lo, double hi);
void requireIntInRange(const std::string& field, int value, int lo, int hi);

}  // namespace reftrack
