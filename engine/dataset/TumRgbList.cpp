#include "engine/dataset/TumRgbList.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "engine/core/DataLines.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

std::vector<StampedImageFile> readTumRgbList(const std::filesystem::path& dir) {
  const std::filesystem::path list = dir / "rgb.txt";
  if (!std::filesystem::is_regular_file(list))
    throw Error("TUM RGB-D folder '" + dir.string() +
                "' has no rgb.txt (expected lines 'timestamp rgb/FILE.png')");
  std::ifstream in(list);
  if (!in) throw Error("TUM RGB-D frame list '" + list.string() + "' cannot be opened");
  std::vector<StampedImageFile> frames;
  forEachDataLine(in, [&](const std::string& line, int lineNo) {
    const std::string where =
        "TUM RGB-D frame list '" + list.string() + "', line " + std::to_string(lineNo);
    std::istringstream ss(line);
    std::string stamp, name, extra;
    ss >> stamp >> name;
    char* end = nullptr;
    const double t = stamp.empty() ? NAN : std::strtod(stamp.c_str(), &end);
    if (name.empty() || !end || *end != '\0' || !std::isfinite(t))
      throw Error(where + ": expected 'timestamp filename'");
    if (ss >> extra) throw Error(where + ": expected 'timestamp filename', got more fields");
    if (!frames.empty() && !(t > frames.back().timestamp))
      throw Error(where + ": timestamp " + stamp + " does not increase");
    const std::filesystem::path file = dir / name;
    std::error_code ec;  // a name the file system refuses (too long, ...) does not exist either
    if (!std::filesystem::is_regular_file(file, ec))
      throw Error(where + ": image '" + file.string() + "' does not exist");
    frames.push_back({t, file});
  });
  if (frames.empty()) throw Error("TUM RGB-D frame list '" + list.string() + "' lists no frame");
  return frames;
}

}  // namespace reftrack
