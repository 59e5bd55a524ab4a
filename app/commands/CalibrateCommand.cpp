// `reftrack calibrate`: camera intrinsics and distortion from images or a video of a chessboard
// or ChArUco board, written as camera.yml; prints the RMS and per-view reprojection errors.
#include <cstdio>
#include <memory>

#include "app/cli/ParsingValidator.hpp"
#include "app/cli/ProgressBar.hpp"
#include "app/commands/Commands.hpp"
#include "engine/calibration/CalibrationInput.hpp"
#include "engine/calibration/CameraCalibrator.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

struct CalibrateOptions {
  std::string board, input, out;
  int maxFrames = 300;
  CalibrationParams params;
};

void runCalibrate(const CalibrateOptions& o) {
  const CalibrationBoard board = CalibrationBoard::parse(o.board);
  CalibrationInput input(o.input, o.maxFrames);
  CameraCalibrator calibrator(board, o.params);
  {
    ProgressBar progress("detecting board", input.size(), input.isVideo() ? "fr" : "img");
    cv::Mat image;
    std::string label;
    while (input.next(image, label)) {
      calibrator.addImage(image, label);
      progress.advance();
    }
    progress.finish();
  }
  const CalibrationResult r = calibrator.calibrate();
  r.camera.save(o.out);

  std::printf("board %s found in %zu of %zu images (%zu rejected); calibrated from %zu views\n",
              board.toString().c_str(), r.viewsFound, r.imagesExamined, r.rejected.size(),
              r.views.size());
  std::printf("RMS reprojection error: %.4f px\n", r.rmsPx);
  std::printf("fx %.3f  fy %.3f  cx %.3f  cy %.3f  (%dx%d)\n", r.camera.fx(), r.camera.fy(),
              r.camera.cx(), r.camera.cy(), r.camera.imageSize().width,
              r.camera.imageSize().height);
  std::printf("distortion:");
  for (double d : r.camera.distortion()) std::printf(" %.6g", d);
  std::printf("\nper-view RMS reprojection error (px):\n");
  for (const CalibrationViewError& v : r.views)
    std::printf("  %-32s %4d corners  %.4f\n", v.label.c_str(), v.corners, v.rmsPx);
  for (const std::string& label : r.rejected)
    std::printf("  %-32s rejected: board not found\n", label.c_str());
  std::printf("wrote %s\n", o.out.c_str());
}

CommandRegistration registerCalibrateCommand(CLI::App& parent) {
  auto options = std::make_shared<CalibrateOptions>();
  CLI::App* sub = parent.add_subcommand(
      "calibrate", "Calibrate the camera (intrinsics, distortion) from views of a board");
  sub->add_option("--board", options->board,
                  "chessboard:COLSxROWS:SQUARE_M (inner corners) or "
                  "charuco:DICT:SQXxSQY:SQUARE_M:MARKER_M")
      ->required()
      ->check(parsingValidator<CalibrationBoard>("BOARD"));
  sub->add_option("--input", options->input,
                  "a folder of images, a glob pattern (quote it) or a video file")
      ->required();
  sub->add_option("--out", options->out, "camera file to write (YAML)")->required();
  sub->add_option("--max-views", options->params.maxViews,
                  "most views used; more are thinned to a spread-out subset")
      ->capture_default_str()
      ->check(CLI::Range(3, 100000));
  sub->add_option("--max-frames", options->maxFrames,
                  "a video is sampled evenly down to at most this many frames")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  sub->add_flag("--fix-aspect", options->params.fixAspectRatio, "force fx = fy");
  sub->add_flag("--zero-tangent", options->params.zeroTangent, "no tangential distortion");
  sub->add_flag("--fix-k3", options->params.fixK3, "no third radial distortion term");
  return {sub, [options] { runCalibrate(*options); }};
}

const CommandRegistrar registrar(20, registerCalibrateCommand);

}  // namespace

}  // namespace reftrack::app
