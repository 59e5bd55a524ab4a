// `reftrack prepare`: the offline preparation (paper Sec. 2, 3.3) for N >= 2 references — poses
// from an ArUco marker (or from a TUM file of known poses), corners of every reference,
// epipolar-guided matches and triangulation (Eq. 9, Eq. 10) per pair, merged into multi-view
// points — written as a version-2 reference map folder.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <optional>

#include "app/cli/ParsingValidator.hpp"
#include "app/commands/Commands.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/TumTrajectory.hpp"
#include "engine/reference/MarkerSpec.hpp"
#include "engine/reference/MultiReferencePreparer.hpp"

namespace reftrack::app {

namespace {

struct PrepareOptions {
  std::string camera, refA, refB, refsFolder, marker, poses, params, out;
  std::vector<std::string> refs;
  std::vector<std::string> images;  // resolved at parse time: --ref..., --refs or --ref-a/--ref-b
};

ReferenceImage readReferenceImage(const std::string& path) {
  cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  if (image.empty())
    throw Error("reference image '" + path + "' cannot be read (not an image, or corrupt)");
  return {image, path};
}

// The image files of a folder, sorted by name (the extensions cv::imread reads).
std::vector<std::string> imagesInFolder(const std::string& folder) {
  static const std::vector<std::string> extensions = {".png", ".jpg",  ".jpeg", ".bmp",
                                                      ".tif", ".tiff", ".webp"};
  std::vector<std::string> out;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (std::find(extensions.begin(), extensions.end(), ext) != extensions.end())
      out.push_back(entry.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

void printPair(const ReferencePairReport& r, const std::vector<std::string>& names) {
  const EpipolarMatchStats& s = r.matching;
  std::printf("pair %d-%d (%s, %s): baseline %.1f mm, view angle %.1f deg: ", r.a, r.b,
              names[static_cast<std::size_t>(r.a)].c_str(),
              names[static_cast<std::size_t>(r.b)].c_str(), r.baselineMetres * 1000.0,
              r.viewAngleDeg);
  if (!r.matched) {
    std::printf("skipped (%s)\n", r.skipped.c_str());
  } else {
    std::printf(
        "%d + %d corners, %d candidate matches of %d pairs, kept %d (RMS %.3f px)%s; dropped: %d "
        "ambiguous, %d correlation peak off the corner, %d behind a camera, %d outside the depth "
        "range, %d low parallax, %d large reprojection error\n",
        s.cornersA, s.cornersB, s.mutualMatches, s.candidatePairs, s.kept, s.reprojectionRmsPx,
        r.merged ? "" : ", too few to merge", s.droppedAmbiguous, s.droppedPeakOffset,
        s.droppedBehindCamera, s.droppedOutsideDepthRange, s.droppedLowParallax,
        s.droppedReprojection);
  }
  std::fflush(stdout);
}

void printSummary(const MultiPreparation& p, const std::vector<std::string>& names,
                  const std::string& out) {
  const MultiPreparationReport& r = p.report;
  std::printf("reference poses: %s\n", p.map.poseSource.c_str());
  for (std::size_t v = 0; v < names.size(); ++v) {
    const ReferenceKeypoints& k = p.map.views[v].keypoints;
    std::printf("reference %zu (%s): %d corners, %zu %s keypoints (%d with a 3D point)", v,
                names[v].c_str(), r.corners[v], k.keypoints.size(), p.map.keypointKind.c_str(),
                k.pointCount());
    if (r.markerRmsPx[v])
      std::printf(", marker corner reprojection RMS %.3f px", *r.markerRmsPx[v]);
    std::printf("\n");
  }
  // Over the merged pairs' kept matches, each against its A corner and B's correlation peak
  // (for two references: the pair's own figure).
  double sq = 0.0;
  int kept = 0;
  for (const ReferencePairReport& pair : r.pairs) {
    if (!pair.merged) continue;
    sq += pair.matching.reprojectionRmsPx * pair.matching.reprojectionRmsPx * pair.matching.kept;
    kept += pair.matching.kept;
  }
  std::printf("reprojection RMS of the kept points: %.3f px over %d pairwise matches\n",
              kept > 0 ? std::sqrt(sq / kept) : 0.0, kept);
  std::printf("map points: %zu; seen by", p.map.points.size());
  for (std::size_t k = 2; k < r.observationHistogram.size(); ++k)
    std::printf(" %zu references: %d%s", k, r.observationHistogram[k],
                k + 1 < r.observationHistogram.size() ? "," : "");
  std::printf("\n");
  std::printf(
      "tracks: %d, dropped %d inconsistent (two corners of one reference), %d observations "
      "above the track reprojection gate, %d points; points seen by 3+ references reproject "
      "with RMS %.3f px\n",
      r.tracks, r.inconsistentTracks, r.droppedObservations, r.droppedPoints, r.multiViewRmsPx);
  std::printf("wrote %s (format version %d, %d references)\n", out.c_str(),
              MultiReferenceMap::kFormatVersion, p.map.size());
}

void runPrepare(const PrepareOptions& o) {
  const PinholeCamera camera = PinholeCamera::load(o.camera);
  const ReferencePreparerParams params =
      o.params.empty() ? ReferencePreparerParams{} : ReferencePreparerParams::load(o.params);
  std::vector<ReferenceImage> images;
  for (const std::string& path : o.images) images.push_back(readReferenceImage(path));
  for (const ReferenceImage& r : images) {
    if (r.image.size() != camera.imageSize())
      throw Error("reference image '" + r.name + "' is " + std::to_string(r.image.cols) + "x" +
                  std::to_string(r.image.rows) + " but camera file '" + o.camera + "' is for " +
                  std::to_string(camera.imageSize().width) + "x" +
                  std::to_string(camera.imageSize().height) + " images");
  }
  const MultiReferencePreparer preparer(camera, params);
  const auto progress = [&](const ReferencePairReport& r) { printPair(r, o.images); };
  std::optional<MultiPreparation> prepared;
  if (!o.marker.empty()) {
    prepared = preparer.prepare(images, MarkerSpec::parse(o.marker), progress);
  } else {
    const TumTrajectory poses = TumTrajectory::load(o.poses);
    if (poses.poses.size() < images.size())
      throw Error("pose file '" + o.poses + "' holds " + std::to_string(poses.poses.size()) +
                  " pose(s); the first two entries are needed (A, then B)");
    std::vector<RigidPose> T;
    for (std::size_t i = 0; i < images.size(); ++i) T.push_back(poses.poses[i].worldToCamera);
    prepared = preparer.prepare(images, T, "poses " + o.poses, progress);
  }
  prepared->map.save(o.out);
  printSummary(*prepared, o.images, o.out);
}

CommandRegistration registerPrepareCommand(CLI::App& parent) {
  auto options = std::make_shared<PrepareOptions>();
  CLI::App* sub = parent.add_subcommand(
      "prepare", "Build the reference map (poses, corners, pairwise matches, 3D points)");
  sub->footer(
      "References: --ref IMG repeated (N >= 2, in order), --refs FOLDER (its images sorted by\n"
      "name) or --ref-a/--ref-b (N = 2). Poses come from an ArUco marker visible in every image\n"
      "(--marker) or from a TUM file with one camera-in-world pose per reference, in order\n"
      "(--poses; with --ref-a/--ref-b its first two entries). Every pair of references with\n"
      "overlap and parallax is matched and triangulated (one progress line per pair); the\n"
      "matches merge into points seen by 2..N references. Writes OUT/map.yml (format version 2)\n"
      "and OUT/reference_00.png, reference_01.png, ...");
  sub->add_option("--camera", options->camera, "camera file (camera.yml)")
      ->required()
      ->check(CLI::ExistingFile);
  CLI::Option* ref = sub->add_option("--ref", options->refs, "reference image (repeat: N >= 2)")
                         ->check(CLI::ExistingFile);
  CLI::Option* refs =
      sub->add_option("--refs", options->refsFolder, "folder of reference images (sorted by name)")
          ->check(CLI::ExistingDirectory);
  CLI::Option* refA =
      sub->add_option("--ref-a", options->refA, "reference image A")->check(CLI::ExistingFile);
  CLI::Option* refB =
      sub->add_option("--ref-b", options->refB, "reference image B")->check(CLI::ExistingFile);
  ref->excludes(refs)->excludes(refA)->excludes(refB);
  refs->excludes(ref)->excludes(refA)->excludes(refB);
  refA->needs(refB);
  refB->needs(refA);
  CLI::Option* marker = sub->add_option("--marker", options->marker,
                                        "marker DICT:ID:SIDE_M, e.g. DICT_6X6_250:23:0.2")
                            ->check(parsingValidator<MarkerSpec>("MARKER"));
  CLI::Option* poses =
      sub->add_option("--poses", options->poses,
                      "TUM file with one pose per reference, in order (--ref-a/--ref-b: first two)")
          ->check(CLI::ExistingFile);
  marker->excludes(poses);
  poses->excludes(marker);
  sub->add_option("--params", options->params,
                  "preparation parameters (YAML: corners, matching, marker, preparation)")
      ->check(CLI::ExistingFile);
  sub->add_option("--out", options->out, "output folder of the reference map")->required();
  sub->callback([options, marker, poses, ref, refs, refA] {
    PrepareOptions& o = *options;
    if (ref->count() == 0 && refs->count() == 0 && refA->count() == 0)
      throw CLI::RequiredError("--ref (repeated), --refs or --ref-a/--ref-b");
    if (marker->count() == 0 && poses->count() == 0)
      throw CLI::RequiredError("one of --marker or --poses");
    if (refA->count() > 0) {
      o.images = {o.refA, o.refB};
      return;  // the pose file's first two entries (checked when read)
    }
    o.images = ref->count() > 0 ? o.refs : imagesInFolder(o.refsFolder);
    if (o.images.size() < 2)
      throw CLI::ValidationError(
          ref->count() > 0 ? "--ref" : "--refs",
          std::to_string(o.images.size()) + " reference image(s); at least 2 are needed");
    if (poses->count() > 0) {
      std::size_t count = 0;
      try {
        count = TumTrajectory::load(o.poses).poses.size();
      } catch (const Error& e) {
        throw CLI::ValidationError("--poses", e.what());
      }
      if (count != o.images.size())
        throw CLI::ValidationError("--poses", "'" + o.poses + "' holds " + std::to_string(count) +
                                                  " pose(s) for " +
                                                  std::to_string(o.images.size()) +
                                                  " reference images (one per image, in order)");
    }
  });
  return {sub, [options] { runPrepare(*options); }};
}

const CommandRegistrar registrar(30, registerPrepareCommand);

}  // namespace

}  // namespace reftrack::app
