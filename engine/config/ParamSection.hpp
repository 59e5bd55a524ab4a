#pragma once
// ParamSection: what every parameter struct offers — check(), write() and read() of its section
// of a YAML parameter file — all three served by the struct's one list of fields
// (ParamFields.hpp). A struct `Params : ParamSection<Params>` declares
//   static constexpr const char* kSection = "name";  // its section ("" for the file's root)
//   template <class Self, class Field> static void fields(Self& self, const Field& field);
// and defines fields() in its .cpp beside `template struct ParamSection<Params>;` (its header
// says `extern template struct ParamSection<Params>;`).
#include <opencv2/core.hpp>

#include "engine/config/YamlNode.hpp"

namespace reftrack {

template <class Params>
struct ParamSection {
  // Throws reftrack::Error naming the first bad field in list order ("parameter 'section.key'
  // must lie in [lo, hi], got v").
  void check() const;
  // The fields as key: value pairs (nested sections as maps) into the open map of fs.
  void write(cv::FileStorage& fs) const;
  // Refuses keys write() does not write (naming the nearest known one), reads every key present
  // (absent ones keep their value; an error names the value's line), then check().
  void read(const YamlNode& node);
};

}  // namespace reftrack
