#pragma once
// AnnotationSet: text labels placed at positions of the stored reference frame (paper Fig. 18),
// drawn at their mapped positions H p in each registered frame. YAML (OpenCV FileStorage):
//   labels:
//     - { text: "Tower", x: 120.5, y: 80.0 }
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace reftrack {

struct Annotation {
  std::string text;
  cv::Point2d position;  // pixels of the reference frame
};

class AnnotationSet {
 public:
  AnnotationSet() = default;
  explicit AnnotationSet(std::vector<Annotation> labels);

  // Throws reftrack::Error naming the file and the entry at fault (missing text, x/y not a
  // finite number, ...).
  static AnnotationSet load(const std::filesystem::path& file);
  void save(const std::filesystem::path& file) const;  // atomic (temp file + rename)

  const std::vector<Annotation>& labels() const { return labels_; }
  bool empty() const { return labels_.empty(); }
  // Positions of every label under H (reference -> frame); NaN for a point mapped to infinity.
  std::vector<cv::Point2d> mapped(const cv::Matx33d& H) const;

 private:
  std::vector<Annotation> labels_;
};

}  // namespace reftrack
