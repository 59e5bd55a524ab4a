#pragma once
// HomographyOverlay: one recorded frame of homography mode — the viewer's composite (video; the
// debug corners, matches and status label when the settings ask: OverlayCompositor) plus the
// reference frame's outline mapped by H and every label drawn at its mapped position
// (render::Annotations2D, paper Fig. 18). Needs a current GL 3.3 context.
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "app/viewer/OverlayCompositor.hpp"
#include "engine/homography/AnnotationSet.hpp"
#include "render/Annotations2D.hpp"
#include "render/RenderTarget.hpp"

namespace reftrack::app {

class HomographyOverlay {
 public:
  HomographyOverlay();
  ~HomographyOverlay();

  // H: reference -> frame when the frame was registered (nullopt: no outline, no labels); between
  // the undistorted images when the camera has distortion (as HomographyFrameTracker gives it).
  // camera: the frame's; referenceSize: the reference's (empty: the frame's);
  // referenceSharesCamera: the reference was recorded through the same lens (else its pixels are
  // used as recorded). Returns the composited BGR image of the frame's size.
  cv::Mat composite(const cv::Mat& frame, const PinholeCamera& camera, const TrackingResult& result,
                    const OverlaySettings& settings, const std::string& label,
                    const std::optional<cv::Matx33d>& H, const AnnotationSet& labels,
                    cv::Size referenceSize = {}, bool referenceSharesCamera = true);

 private:
  OverlayCompositor compositor_;
  render::Annotations2D annotations_;
  std::unique_ptr<render::RenderTarget> target_;
};

}  // namespace reftrack::app
