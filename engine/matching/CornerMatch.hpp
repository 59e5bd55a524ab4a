#pragma once
// CornerMatch: index `first` into the first point set matched to index `second` of the second,
// with its correlation score.
#include <vector>

namespace reftrack {

struct CornerMatch {
  int first = -1;
  int second = -1;
  float score = 0.0f;
};

}  // namespace reftrack
