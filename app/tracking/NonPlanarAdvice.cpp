#include "app/tracking/NonPlanarAdvice.hpp"

namespace reftrack::app {

void NonPlanarAdvice::add(const HomographyTrackResult& result) {
  recent_.push_back({!result.tracked,
                     !result.tracked && result.failure.find("refused by the registration check") !=
                                            std::string::npos});
  if (static_cast<int>(recent_.size()) > kWindow) recent_.pop_front();
  if (advice()) everShown_ = true;
}

std::optional<std::string> NonPlanarAdvice::advice() const {
  int lost = 0, refused = 0;
  for (const Outcome& o : recent_) {
    lost += o.lost ? 1 : 0;
    refused += o.refused ? 1 : 0;
  }
  if (lost < kMinLost || refused < kMinRefused) return std::nullopt;
  return message();
}

const char* NonPlanarAdvice::message() {
  return "homography mode follows one flat surface: this view does not fit one homography (a 3-D "
         "object, or things moving in front of the target). Use a reference image cropped to one "
         "flat face of the object, or build a map of it (reftrack prepare) and track in 6-DOF "
         "mode.";
}

}  // namespace reftrack::app
