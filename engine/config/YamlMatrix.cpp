#include "engine/config/YamlMatrix.hpp"

#include <cmath>
#include <string>

#include "engine/config/KnownKeys.hpp"

namespace reftrack {

namespace {

struct ElementType {
  int depth = -1;
  int channels = 0;
};

// "d" -> CV_64F x 1, "3f" -> CV_32F x 3; depth -1 when `dt` is not that form or has more
// channels than OpenCV allows (CV_CN_MAX).
ElementType elementTypeOf(const std::string& dt) {
  std::size_t digits = 0;
  while (digits < dt.size() && dt[digits] >= '0' && dt[digits] <= '9') ++digits;
  if (digits + 1 != dt.size() || digits > 3) return {};
  const std::string letters = "ucwsifdh";
  const int depths[] = {CV_8U, CV_8S, CV_16U, CV_16S, CV_32S, CV_32F, CV_64F, CV_16F};
  const std::size_t letter = letters.find(dt.back());
  if (letter == std::string::npos) return {};
  const int channels = digits == 0 ? 1 : std::stoi(dt.substr(0, digits));
  if (channels < 1 || channels > CV_CN_MAX) return {};
  return {depths[letter], channels};
}

// The range of an integer depth's values.
bool fitsDepth(double v, int depth) {
  if (depth == CV_32F || depth == CV_64F || depth == CV_16F) return true;
  if (!std::isfinite(v) || v != std::floor(v)) return false;
  switch (depth) {
    case CV_8U:
      return v >= 0 && v <= 255;
    case CV_8S:
      return v >= -128 && v <= 127;
    case CV_16U:
      return v >= 0 && v <= 65535;
    case CV_16S:
      return v >= -32768 && v <= 32767;
    default:
      return v >= -2147483648.0 && v <= 2147483647.0;
  }
}

[[noreturn]] void invalid(const YamlNode& matrix, const YamlNode& at, const std::string& why) {
  at.fail(matrix.name() + " is not a valid matrix: " + why);
}

}  // namespace

cv::Mat readYamlMatrix(const YamlNode& node) {
  const auto bad = [&](const YamlNode& at, const std::string& why) { invalid(node, at, why); };
  if (!node.present()) node.fail(node.name() + " is missing");
  if (!node.isMap()) bad(node, "it must be a map of rows, cols, dt and data (!!opencv-matrix)");
  requireKnownKeys(node, {"rows", "cols", "dt", "data"});
  const auto count = [&](const char* key) {
    const YamlNode n = node[key];
    const std::optional<int> v = n.integer();
    if (!v || *v < 0) invalid(node, n, std::string("'") + key + "' must be a count");
    return *v;
  };
  const int rows = count("rows"), cols = count("cols");
  const YamlNode dt = node["dt"];
  const ElementType type = elementTypeOf(dt.text().value_or(""));
  if (type.depth < 0) bad(dt, "'dt' must be an element type such as d or 3f");
  const long long values = static_cast<long long>(rows) * cols * type.channels;
  if (values > (1LL << 31) - 1) bad(node, "it is too large");
  const YamlNode data = node["data"];
  const long long given = data.isList() ? static_cast<long long>(data.size()) : 0;
  if (data.present() && !data.isList() && !data.isNull()) bad(data, "'data' must be a list");
  if (given != values)
    bad(data.present() ? data : node, "its header asks for " + std::to_string(values) +
                                          " values but 'data' holds " + std::to_string(given));
  cv::Mat m(rows, cols, CV_MAKETYPE(type.depth, type.channels));
  cv::Mat asDouble(1, static_cast<int>(values), CV_64F);
  for (int i = 0; i < static_cast<int>(values); ++i) {
    const YamlNode item = data.item(static_cast<std::size_t>(i));
    const std::optional<double> v = item.number();
    if (!v) invalid(node, item, "'data' must hold numbers only");
    if (!fitsDepth(*v, type.depth))
      bad(item, "'data' holds " + *item.text() + ", which dt '" + *dt.text() + "' cannot hold");
    asDouble.at<double>(0, i) = *v;
  }
  if (values > 0) asDouble.reshape(type.channels, rows).convertTo(m, m.type());
  return m;
}

}  // namespace reftrack
