#include "engine/homography/AnnotationSet.hpp"

#include <cmath>
#include <limits>

#include "engine/config/ConfigFile.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"
#include "engine/homography/HomographyDlt.hpp"

namespace reftrack {

AnnotationSet::AnnotationSet(std::vector<Annotation> labels) : labels_(std::move(labels)) {
  for (size_t i = 0; i < labels_.size(); ++i)
    if (!std::isfinite(labels_[i].position.x) || !std::isfinite(labels_[i].position.y))
      throw Error("label " + std::to_string(i) + " has a non-finite position");
}

AnnotationSet AnnotationSet::load(const std::filesystem::path& file) {
  const std::string where = "labels file '" + file.string() + "'";
  if (!std::filesystem::exists(file)) throw Error(where + " does not exist");
  const YamlNode root = readConfigFile(file, where);
  std::vector<Annotation> labels;
  try {
    requireKnownKeys(root, {"labels"});
    const YamlNode list = root["labels"];
    if (!list.present()) throw Error("missing key 'labels'");
    if (!list.isList()) list.fail("'labels' must be a list of {text, x, y}");
    for (const YamlNode& n : list.children()) {
      if (!n.isMap()) n.fail(n.name() + " must be a map {text, x, y}");
      requireKnownKeys(n, {"text", "x", "y"});
      Annotation a;
      const YamlNode t = n["text"], x = n["x"], y = n["y"];
      if (!t.text()) n.fail(n.name() + ": 'text' is missing or not text");
      a.text = *t.text();
      for (const YamlNode& c : {x, y})
        if (!c.number()) n.fail(n.name() + ": '" + c.key() + "' is missing or not a number");
      a.position = {*x.number(), *y.number()};
      if (!std::isfinite(a.position.x) || !std::isfinite(a.position.y))
        n.fail(n.name() + ": position must be finite (got NaN/inf)");
      labels.push_back(std::move(a));
    }
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  return AnnotationSet(std::move(labels));
}

void AnnotationSet::save(const std::filesystem::path& file) const {
  writeFileAtomically(file, [&](const std::filesystem::path& tmp) {
    cv::FileStorage fs(tmp.string(), cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
    if (!fs.isOpened()) throw Error("cannot write labels file '" + file.string() + "'");
    fs << "labels"
       << "[";
    for (const Annotation& a : labels_)
      fs << "{"
         << "text" << a.text << "x" << a.position.x << "y" << a.position.y << "}";
    fs << "]";
    fs.release();
  });
}

std::vector<cv::Point2d> AnnotationSet::mapped(const cv::Matx33d& H) const {
  std::vector<cv::Point2d> out;
  out.reserve(labels_.size());
  for (const Annotation& a : labels_) {
    const cv::Point2d q = transferPoint(H, a.position);
    const bool finite = std::isfinite(q.x) && std::isfinite(q.y);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    out.push_back(finite ? q : cv::Point2d(nan, nan));
  }
  return out;
}

}  // namespace reftrack
