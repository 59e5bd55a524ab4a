#include "app/tracking/HomographyTrack.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "app/cli/Interruption.hpp"
#include "app/cli/ProgressBar.hpp"
#include "app/sources/InputCamera.hpp"
#include "app/tracking/HomographyOverlay.hpp"
#include "app/tracking/HomographyTrackCsv.hpp"
#include "app/tracking/TrackInput.hpp"
#include "app/viewer/HomographyFrameTracker.hpp"
#include "app/viewer/VideoRecorder.hpp"
#include "engine/core/Error.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {

namespace {

// `image` scaled to fit `size` (aspect kept, centred on black): a frame of another size than the
// recording's first (an image folder of several cameras' photos) in the recording.
cv::Mat fitInto(const cv::Mat& image, cv::Size size) {
  if (image.size() == size) return image;
  const double s = std::min(static_cast<double>(size.width) / image.cols,
                            static_cast<double>(size.height) / image.rows);
  const cv::Size fitted(std::max(1, static_cast<int>(std::lround(image.cols * s))),
                        std::max(1, static_cast<int>(std::lround(image.rows * s))));
  cv::Mat scaled, out(size, image.type(), cv::Scalar::all(0));
  cv::resize(image, scaled, fitted, 0, 0, cv::INTER_AREA);
  scaled.copyTo(out(cv::Rect((size.width - fitted.width) / 2, (size.height - fitted.height) / 2,
                             fitted.width, fitted.height)));
  return out;
}

}  // namespace

HomographyTrackSummary runHomographyTrack(const HomographyTrackOptions& o) {
  cv::Mat reference;
  try {
    reference = cv::imread(o.reference.string(), cv::IMREAD_COLOR);
  } catch (const cv::Exception& e) {
    throw Error("reference image '" + o.reference.string() + "' cannot be read: " + e.err);
  }
  if (reference.empty())
    throw Error("reference image '" + o.reference.string() + "' is missing or not an image");
  TrackerParams params = o.params.empty() ? TrackerParams{} : TrackerParams::load(o.params);
  params.mode = TrackingMode::Homography;
  params.check();
  const AnnotationSet labels = o.labels.empty() ? AnnotationSet{} : AnnotationSet::load(o.labels);

  // The camera is the frames' camera (it fixes their size); without one, frames may have any
  // size (all of the first frame's), whatever the reference's. A calibrated camera enables the
  // rotation-only model for a reference of its size; without one, the overlay still needs a
  // camera of the frame size (homography mode draws no 3-D content, so any pinhole serves).
  // Without --camera, a euroc: input brings its sensor.yaml camera (cameraFromInput says so).
  const std::optional<PinholeCamera> calibrated =
      o.camera.empty() ? cameraFromInput(o.input)
                       : std::optional<PinholeCamera>(PinholeCamera::load(o.camera));
  TrackInput input =
      calibrated ? TrackInput(o.input, calibrated->imageSize(), "the camera is calibrated for",
                              o.maxFrames, !o.record.empty())
                 : TrackInput::anySize(o.input, reference.size(), o.maxFrames, !o.record.empty());
  HomographyFrameTracker tracker(reference, params, calibrated, labels);
  std::optional<PinholeCamera> camera = calibrated;  // the overlay's (set at the first frame)
  std::unique_ptr<HomographyOverlay> overlay;
  std::unique_ptr<VideoRecorder> recorder;
  OverlaySettings settings;
  settings.setDebugLayers(o.debugOverlay);
  if (!o.record.empty()) overlay = std::make_unique<HomographyOverlay>();

  std::vector<HomographyFrameRecord> records;
  ProgressBar progress("track homography", static_cast<std::size_t>(input.expectedCount()));
  HomographyTrackSummary summary;
  std::vector<double> ms;
  const InterruptibleWork interruptible;  // Ctrl-C ends the loop; the outputs are then finished
  while (!interruptRequested()) {
    const std::optional<Frame> frame = input.next();
    if (!frame) break;
    const auto t0 = std::chrono::steady_clock::now();
    const TrackingResult result = tracker.process(frame->image, frame->index, frame->timestamp);
    const double elapsed =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const HomographyTrackResult& r = tracker.last();
    HomographyFrameRecord record;
    record.index = frame->index;
    record.timestamp = frame->timestamp;
    record.tracked = r.tracked;
    record.inlierRatio = r.inlierRatio;
    if (r.tracked) record.H = r.H;
    if (!r.tracked) record.reason = r.failure;
    record.milliseconds = elapsed;
    records.push_back(record);
    ms.push_back(elapsed);
    summary.tracked += r.tracked ? 1 : 0;
    if (overlay) {
      if (camera && camera->imageSize() != frame->image.size()) camera.reset();
      if (!camera) camera = PinholeCamera::fromFieldOfView(frame->image.size(), 60.0);
      if (!recorder)
        recorder =
            std::make_unique<VideoRecorder>(o.record, input.source().fps(), frame->image.size());
      const std::optional<cv::Matx33d> H =
          r.tracked ? std::optional<cv::Matx33d>(r.H) : std::nullopt;
      const cv::Mat composite =
          overlay->composite(frame->image, *camera, result, settings,
                             "frame " + std::to_string(frame->index) + "  " + result.status, H,
                             labels, tracker.referenceSize(), tracker.referenceSharesCamera());
      recorder->write(fitInto(composite, recorder->frameSize()), frame->timestamp, std::nullopt);
    }
    ++summary.frames;
    progress.advance();
  }
  progress.finish();
  input.requireFrames();
  // A recording that cannot be finished (full disk) must not cost the CSV.
  const std::string recordingError = closeRecording(recorder.get());
  if (!o.csv.empty()) writeHomographyCsv(o.csv, records);
  if (!recordingError.empty()) throw Error(recordingError);
  input.throwIfCutShort();
  std::nth_element(ms.begin(), ms.begin() + static_cast<long>(ms.size() / 2), ms.end());
  summary.medianMs = ms[ms.size() / 2];
  if (tracker.advice().everShown()) summary.advice = NonPlanarAdvice::message();
  return summary;
}

}  // namespace reftrack::app
