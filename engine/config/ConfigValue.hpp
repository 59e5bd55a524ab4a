#pragma once
// Typed reading of one key of a parameter section (a YamlNode map). A missing key leaves the
// value unchanged (the default); a value of the wrong type, NaN or infinity throws
// reftrack::Error naming its line and "section.key".
#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <string>

#include "engine/config/YamlNode.hpp"

namespace reftrack {

void readConfigValue(const YamlNode& section, const std::string& key, double& value);
void readConfigValue(const YamlNode& section, const std::string& key, int& value);
void readConfigValue(const YamlNode& section, const std::string& key, bool& value);
void readConfigValue(const YamlNode& section, const std::string& key, std::string& value);

// Opens a YAML parameter file (readConfigFile) and hands its root to `read`; every failure
// (missing, unparsable, an unknown or bad entry) throws reftrack::Error naming the file.
void readParameterFile(const std::filesystem::path& file,
                       const std::function<void(const YamlNode& root)>& read);
// The same for parameters given as YAML text (or JSON, which is YAML); `what` names them in
// messages ("parameters (dict)").
void readParameterText(const std::string& text, const std::string& what,
                       const std::function<void(const YamlNode& root)>& read);
// Writes a YAML parameter file atomically (temp file + rename): `write` fills its root map.
void writeParameterFile(const std::filesystem::path& file,
                        const std::function<void(cv::FileStorage& fs)>& write);

// Runs `check` (a struct's check() after reading `root`); its error "parameter 'a.b' ..." gets
// the line of a.b when `root` gives that value (as the field rules of ParamFields.hpp do).
void checkWithLines(const YamlNode& root, const std::function<void()>& check);

// Throws reftrack::Error "parameter '<field>' must ..." unless value is finite and within [lo, hi].
void requireFiniteInRange(const std::string& field, double value, double lo, double hi);
void requireIntInRange(const std::string& field, int value, int lo, int hi);

}  // namespace reftrack
