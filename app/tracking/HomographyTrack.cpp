#include "app/tracking/HomographyTrack.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "app/cli/Interruption.hpp"
#include "app/cli/ProgressBar.hpp"
#include "app/sources/FrameSourceFactory.hpp"
#include "app/sources/InputCamera.hpp"
#include "app/tracking/HomographyOverlay.hpp"
#include "app/tracking/HomographyTrackCsv.hpp"
#include "app/viewer/HomographyFrameTracker.hpp"
#include "app/viewer/VideoRecorder.hpp"
#include "engine/core/Error.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {

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

  std::unique_ptr<render::GlContext> gl;
  if (isSimulatorInput(o.input) || !o.record.empty()) gl = render::createHeadlessContext();
  FrameSourceOptions sourceOptions;
  sourceOptions.simSize = reference.size();
  std::unique_ptr<FrameSource> source = openFrameSource(o.input, sourceOptions);

  // A calibrated camera enables the rotation-only model; without one, the overlay still needs a
  // camera of the frame size (homography mode draws no 3-D content, so any pinhole serves).
  // Without --camera, a euroc: input brings its sensor.yaml camera (cameraFromInput says so).
  const std::optional<PinholeCamera> calibrated =
      o.camera.empty() ? cameraFromInput(o.input)
                       : std::optional<PinholeCamera>(PinholeCamera::load(o.camera));
  HomographyFrameTracker tracker(reference, params, calibrated, labels);
  const PinholeCamera camera =
      calibrated ? *calibrated : PinholeCamera::fromFieldOfView(reference.size(), 60.0);
  std::unique_ptr<HomographyOverlay> overlay;
  std::unique_ptr<VideoRecorder> recorder;
  const OverlaySettings settings;
  if (!o.record.empty()) {
    overlay = std::make_unique<HomographyOverlay>();
    recorder = std::make_unique<VideoRecorder>(o.record, source->fps(), reference.size());
  }

  std::vector<HomographyFrameRecord> records;
  const int total = o.maxFrames > 0
                        ? std::min(o.maxFrames, source->frameCount().value_or(o.maxFrames))
                        : source->frameCount().value_or(0);
  ProgressBar progress("track homography", static_cast<std::size_t>(std::max(total, 0)));
  HomographyTrackSummary summary;
  std::vector<double> ms;
  // A frame that cannot be read or used mid-stream ends the run like the end of the input, so
  // everything written up to it is kept; the error is reported after the outputs are finished.
  std::string streamError;
  const InterruptibleWork interruptible;  // Ctrl-C ends the loop; the outputs are then finished
  while ((o.maxFrames < 0 || summary.frames < o.maxFrames) && !interruptRequested()) {
    std::optional<Frame> frame;
    try {
      frame = source->next();
    } catch (const Error& e) {
      streamError = e.what();
      break;
    }
    if (!frame) break;
    if (frame->image.size() != reference.size()) {
      streamError = "input '" + o.input + "' frame " + std::to_string(frame->index) + " is " +
                    std::to_string(frame->image.cols) + "x" + std::to_string(frame->image.rows) +
                    " but the reference '" + o.reference.string() + "' is " +
                    std::to_string(reference.cols) + "x" + std::to_string(reference.rows);
      if (summary.frames == 0) throw Error(streamError);
      break;
    }
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
    if (recorder) {
      const std::optional<cv::Matx33d> H =
          r.tracked ? std::optional<cv::Matx33d>(r.H) : std::nullopt;
      const cv::Mat composite = overlay->composite(
          frame->image, camera, result, settings,
          "frame " + std::to_string(frame->index) + "  " + result.status, H, labels);
      recorder->write(composite, frame->timestamp, std::nullopt);
    }
    ++summary.frames;
    progress.advance();
  }
  progress.finish();
  if (summary.frames == 0)
    throw Error(streamError.empty() ? "input '" + o.input + "' gave no frames" : streamError);
  // A recording that cannot be finished (full disk) must not cost the CSV.
  std::string recordingError;
  if (recorder) try {
      recorder->close();
    } catch (const Error& e) {
      recordingError = e.what();
    }
  if (!o.csv.empty()) writeHomographyCsv(o.csv, records);
  if (!recordingError.empty()) throw Error(recordingError);
  if (!streamError.empty())
    throw Error(streamError + " (outputs written up to frame " +
                std::to_string(records.back().index) + ")");
  std::nth_element(ms.begin(), ms.begin() + static_cast<long>(ms.size() / 2), ms.end());
  summary.medianMs = ms[ms.size() / 2];
  return summary;
}

}  // namespace reftrack::app
