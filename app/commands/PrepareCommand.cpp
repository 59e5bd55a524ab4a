// `reftrack prepare`: the offline preparation (paper Sec. 2, 3.3) — reference poses from an ArUco
// marker (or from a TUM file of known poses), corners of both reference images, epipolar-guided
// A<->B matches, triangulation (Eq. 9, Eq. 10) — written as a reference map folder.
#include <cstdio>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <optional>

#include "app/cli/ParsingValidator.hpp"
#include "app/commands/Commands.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/TumTrajectory.hpp"
#include "engine/reference/MarkerSpec.hpp"
#include "engine/reference/ReferencePreparer.hpp"

namespace reftrack::app {

namespace {

struct PrepareOptions {
  std::string camera, refA, refB, marker, poses, params, out;
};

ReferenceImage readReferenceImage(const std::string& path) {
  cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  if (image.empty())
    throw Error("reference image '" + path + "' cannot be read (not an image, or corrupt)");
  return {image, path};
}

void printSummary(const Preparation& p, const std::string& nameA, const std::string& nameB,
                  const std::string& out) {
  const PreparationReport& r = p.report;
  const EpipolarMatchStats& s = r.matching;
  std::printf("reference poses: %s (baseline %.1f mm)\n", p.map.poseSource.c_str(),
              r.baselineMetres * 1000.0);
  if (r.markerRmsA && r.markerRmsB) {
    std::printf("marker corner reprojection RMS: %.3f px in %s, %.3f px in %s\n", *r.markerRmsA,
                nameA.c_str(), *r.markerRmsB, nameB.c_str());
  }
  std::printf("corners: %d in A, %d in B\n", s.cornersA, s.cornersB);
  std::printf("candidate matches (epipolar + depth gates, NCC, mutual best): %d of %d pairs\n",
              s.mutualMatches, s.candidatePairs);
  std::printf(
      "kept %d; dropped: %d ambiguous, %d correlation peak off the corner, %d behind a camera, %d "
      "outside the depth range, %d low "
      "parallax, %d large reprojection error\n",
      s.kept, s.droppedAmbiguous, s.droppedPeakOffset, s.droppedBehindCamera,
      s.droppedOutsideDepthRange, s.droppedLowParallax, s.droppedReprojection);
  std::printf("reprojection RMS of the kept points: %.3f px; matches cover %d of 12 image cells\n",
              s.reprojectionRmsPx, r.occupiedGridCells);
  std::printf("wrote %s\n", out.c_str());
}

void runPrepare(const PrepareOptions& o) {
  const PinholeCamera camera = PinholeCamera::load(o.camera);
  const ReferencePreparerParams params =
      o.params.empty() ? ReferencePreparerParams{} : ReferencePreparerParams::load(o.params);
  const ReferenceImage a = readReferenceImage(o.refA);
  const ReferenceImage b = readReferenceImage(o.refB);
  for (const ReferenceImage* r : {&a, &b}) {
    if (r->image.size() != camera.imageSize())
      throw Error("reference image '" + r->name + "' is " + std::to_string(r->image.cols) + "x" +
                  std::to_string(r->image.rows) + " but camera file '" + o.camera + "' is for " +
                  std::to_string(camera.imageSize().width) + "x" +
                  std::to_string(camera.imageSize().height) + " images");
  }
  const ReferencePreparer preparer(camera, params);
  std::optional<Preparation> prepared;
  if (!o.marker.empty()) {
    prepared = preparer.prepare(a, b, MarkerSpec::parse(o.marker));
  } else {
    const TumTrajectory poses = TumTrajectory::load(o.poses);
    if (poses.poses.size() < 2)
      throw Error("pose file '" + o.poses + "' holds " + std::to_string(poses.poses.size()) +
                  " pose(s); the first two entries are needed (A, then B)");
    prepared = preparer.prepare(a, b, poses.poses[0].worldToCamera, poses.poses[1].worldToCamera,
                                "poses " + o.poses);
  }
  prepared->map.save(o.out);
  printSummary(*prepared, o.refA, o.refB, o.out);
}

CommandRegistration registerPrepareCommand(CLI::App& parent) {
  auto options = std::make_shared<PrepareOptions>();
  CLI::App* sub = parent.add_subcommand(
      "prepare", "Build the reference map (poses, corners, A<->B matches, 3D points)");
  sub->footer(
      "Reference poses come from an ArUco marker visible in both images (--marker) or from a\n"
      "TUM file whose first two entries are the camera-in-world poses of A and B (--poses).\n"
      "Writes OUT/map.yml, OUT/reference_a.png and OUT/reference_b.png.");
  sub->add_option("--camera", options->camera, "camera file (camera.yml)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--ref-a", options->refA, "reference image A")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--ref-b", options->refB, "reference image B")
      ->required()
      ->check(CLI::ExistingFile);
  CLI::Option* marker = sub->add_option("--marker", options->marker,
                                        "marker DICT:ID:SIDE_M, e.g. DICT_6X6_250:23:0.2")
                            ->check(parsingValidator<MarkerSpec>("MARKER"));
  CLI::Option* poses =
      sub->add_option("--poses", options->poses, "TUM file with the poses of A and B (first two)")
          ->check(CLI::ExistingFile);
  marker->excludes(poses);
  poses->excludes(marker);
  sub->add_option("--params", options->params,
                  "preparation parameters (YAML: corners, matching, marker, preparation)")
      ->check(CLI::ExistingFile);
  sub->add_option("--out", options->out, "output folder of the reference map")->required();
  sub->callback([marker, poses] {
    if (marker->count() == 0 && poses->count() == 0)
      throw CLI::RequiredError("one of --marker or --poses");
  });
  return {sub, [options] { runPrepare(*options); }};
}

const CommandRegistrar registrar(30, registerPrepareCommand);

}  // namespace

}  // namespace reftrack::app
