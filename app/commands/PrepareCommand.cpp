// `reftrack prepare`: the offline preparation (paper Sec. 2, 3.3) for N >= 2 references — poses
// from an ArUco marker (or from a TUM file of known poses, or, `--unprepared`, from the
// references' own matches and one known distance), corners of every reference, epipolar-guided
// matches and triangulation (Eq. 9, Eq. 10) per pair, merged into multi-view points — written as
// a version-3 reference map folder.
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
#include "app/sources/FrameSourceFactory.hpp"
#include "app/sources/InputCamera.hpp"
#include "app/sources/StampedImageSource.hpp"
#include "engine/config/ConfigValue.hpp"
#include "engine/core/Error.hpp"
#include "engine/dataset/DatasetGroundTruth.hpp"
#include "engine/evaluation/TrajectoryInterpolation.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/TumTrajectory.hpp"
#include "engine/mapping/UnpreparedInitializer.hpp"
#include "engine/reference/MarkerSpec.hpp"
#include "engine/reference/MultiReferencePreparer.hpp"

namespace reftrack::app {

namespace {

struct PrepareOptions {
  std::string camera, refA, refB, refsFolder, marker, poses, params, out, input;
  std::vector<std::string> refs;
  std::vector<int> refFrames;       // with --input: the frames that become references
  std::vector<std::string> images;  // resolved at parse time: --ref..., --refs or --ref-a/--ref-b
  // --unprepared: the poses from the references' own matches, the scale from --baseline or
  // --distance with --distance-points (x1, y1, x2, y2 in the first reference).
  bool unprepared = false;
  double baseline = 0.0, distance = 0.0;
  std::vector<double> distancePoints;
};

// A length in metres: a usage error unless a finite number greater than 0.
const CLI::Validator kPositiveMetres(
    [](std::string& v) -> std::string {
      double x = 0.0;
      if (!CLI::detail::lexical_cast(v, x) || !std::isfinite(x) || !(x > 0.0))
        return "must be a finite length in metres greater than 0, got '" + v + "'";
      return "";
    },
    "METRES");

// A pixel coordinate: a finite number.
const CLI::Validator kFiniteNumber(
    [](std::string& v) -> std::string {
      double x = 0.0;
      if (!CLI::detail::lexical_cast(v, x) || !std::isfinite(x))
        return "must be a finite number, got '" + v + "'";
      return "";
    },
    "NUMBER");

bool isDatasetSpec(const std::string& s) {
  return s.rfind("tum:", 0) == 0 || s.rfind("euroc:", 0) == 0;
}

// Ground-truth samples farther apart than this are not interpolated across (s).
constexpr double kMaxGroundTruthGap = 0.05;

// The reference frames of a sequence (--input, --ref-frames): images, names (the image file of a
// dataset frame, else "INPUT#N") and timestamps.
struct SequenceReferences {
  std::vector<ReferenceImage> images;
  std::vector<std::string> names;
  std::vector<double> timestamps;
};

SequenceReferences readSequenceReferences(const PrepareOptions& o) {
  const std::unique_ptr<FrameSource> source = openFrameSource(o.input);
  const auto* stamped = dynamic_cast<const StampedImageSource*>(source.get());
  SequenceReferences refs;
  for (int index : o.refFrames) {
    const std::optional<int> count = source->frameCount();
    if (count && index >= *count)
      throw Error("--ref-frames: frame " + std::to_string(index) + " is beyond the " +
                  std::to_string(*count) + " frames of " + source->description());
    source->seek(index);
    const std::optional<Frame> frame = source->next();
    if (!frame)
      throw Error("--ref-frames: " + source->description() + " has no frame " +
                  std::to_string(index));
    const std::string name = stamped
                                 ? stamped->frames()[static_cast<std::size_t>(index)].file.string()
                                 : o.input + "#" + std::to_string(index);
    refs.images.push_back({frame->image, name});
    refs.names.push_back(name);
    refs.timestamps.push_back(frame->timestamp);
  }
  return refs;
}

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
  std::printf("pair %d-%d (%s, %s)%s: baseline %.1f mm, view angle %.1f deg: ", r.a, r.b,
              names[static_cast<std::size_t>(r.a)].c_str(),
              names[static_cast<std::size_t>(r.b)].c_str(),
              r.denserCorners ? ", denser corners" : "", r.baselineMetres * 1000.0, r.viewAngleDeg);
  if (!r.matched) {
    std::printf("skipped (%s)\n", r.skipped.c_str());
  } else {
    std::printf(
        "%d + %d corners, %d candidate matches of %d pairs, kept %d (RMS %.3f px)%s; dropped: %d "
        "ambiguous, %d correlation peak off the corner, %d behind a camera, %d outside the depth "
        "range, %d low parallax, %d large reprojection error, %d a look-alike on the epipolar "
        "line\n",
        s.cornersA, s.cornersB, s.mutualMatches, s.candidatePairs, s.kept, s.reprojectionRmsPx,
        r.merged ? "" : ", too few to merge", s.droppedAmbiguous, s.droppedPeakOffset,
        s.droppedBehindCamera, s.droppedOutsideDepthRange, s.droppedLowParallax,
        s.droppedReprojection, s.droppedLineRival);
    if (s.poseFit)
      std::printf(
          "  poses against the images: %d probe pairs, %d fit the images' own relative pose "
          "(rotation %.2f deg, translation direction %.2f deg from the given); their median "
          "distance to the epipolar lines: %.2f px under the given poses, %.2f px under the "
          "images' pose: %s\n",
          s.probeMatches, s.poseFit->inliers, s.poseFit->rotationChangeDeg,
          s.poseFit->translationDirectionChangeDeg, s.poseFit->givenMedianPx,
          s.poseFit->fittedMedianPx,
          s.posesDisagree ? "they disagree, matched along the images' lines"
                          : "the given poses agree with the images");
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
  if (r.pointsBeforeDenserCorners >= 0)
    std::printf(
        "the references' corners gave %d map points (fewer than preparation.target_points, "
        "corners repeating %.2f): with denser corners %d; kept the %s\n",
        r.pointsBeforeDenserCorners, r.cornerRepeat,
        r.denserCorners ? static_cast<int>(p.map.points.size()) : r.denserCornersGave,
        r.denserCorners ? "denser corners' map" : "first map");
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
  if (r.poseRefinement) {
    std::printf(
        "reference poses refined from the matches (reference 0 held): reprojection RMS "
        "%.3f -> %.3f px over %d observations;",
        r.poseRefinement->initialRmsPx, r.poseRefinement->finalRmsPx,
        r.poseRefinement->observations);
    for (std::size_t v = 1; v < r.poseRefinement->movedDeg.size(); ++v)
      std::printf(" %zu moved %.2f mm, %.3f deg%s", v, r.poseRefinement->movedMillimetres[v],
                  r.poseRefinement->movedDeg[v],
                  v + 1 < r.poseRefinement->movedDeg.size() ? "," : "");
    std::printf("\n");
  }
  std::printf("wrote %s (format version %d, %d references)\n", out.c_str(),
              MultiReferenceMap::kFormatVersion, p.map.size());
}

// What an unprepared map's preparation printed beyond a posed one's: the motion, the rounds, the
// plane and the scale, and the references added to the first two.
void printUnprepared(const UnpreparedMapReport& r) {
  std::printf("two-view motion of references 0-1: %s\n", r.motion.summary().c_str());
  std::printf("refined from %d start(s); the best fit from the %s:\n", r.starts, r.start.c_str());
  for (std::size_t i = 0; i < r.rounds.size(); ++i) {
    const UnpreparedRound& k = r.rounds[i];
    std::printf(
        "round %zu: %d points from the corner matches, reprojection RMS %.3f -> %.3f px; the "
        "refinement turned reference 1 by %.3f deg and its direction by %.3f deg\n",
        i + 1, k.points, k.rmsBeforePx, k.rmsAfterPx, k.turnedDeg, k.directionDeg);
  }
  if (r.onPlane)
    std::printf(
        "world frame: on the dominant plane (%d of the %d points near the scene's middle within "
        "its band, RMS %.2f mm), origin at their centre, z toward the cameras\n",
        r.planePoints, r.planeConsideredPoints, 1000.0 * r.planeRmsMetres);
  else
    std::printf("world frame: reference 0's camera (no dominant plane: %s)\n", r.planeNote.c_str());
  std::printf("scale: %s; baseline of references 0-1 %.4f m", r.scale.toString().c_str(),
              r.baselineMetres);
  if (r.scale.kind == MetricScale::Kind::Distance)
    std::printf("; the points on the plane at (%.4f, %.4f, %.4f) and (%.4f, %.4f, %.4f) m",
                r.distanceFirst.x(), r.distanceFirst.y(), r.distanceFirst.z(), r.distanceSecond.x(),
                r.distanceSecond.y(), r.distanceSecond.z());
  std::printf("\n");
  for (const AddedReference& a : r.added)
    std::printf(
        "reference %d added as `extend` adds one: matched to %zu reference(s), %d points "
        "extended, %d new; adjustment RMS %.3f -> %.3f px\n",
        a.view, a.matchedViews.size(), a.pointsExtended, a.pointsAdded, a.adjustment.initialRmsPx,
        a.adjustment.finalRmsPx);
  if (r.closingAdjustment)
    std::printf("closing bundle adjustment: RMS %.3f -> %.3f px over %d observations\n",
                r.closingAdjustment->initialRmsPx, r.closingAdjustment->finalRmsPx,
                r.closingAdjustment->observations);
  std::fflush(stdout);
}

// `--params` of an unprepared preparation: the preparation's sections and `unprepared`,
// `extension`, `bundle_adjustment` (for the references after the first two).
void loadUnpreparedParams(const std::string& file, MapExtenderParams& extender,
                          UnpreparedMapParams& unprepared) {
  if (file.empty()) return;
  readParameterFile(file, [&](const YamlNode& root) {
    unprepared.read(root["unprepared"]);
    extender.extension.read(root["extension"]);
    extender.bundleAdjustment.read(root["bundle_adjustment"]);
    extender.preparation.read(root, {"unprepared", "extension", "bundle_adjustment"});
  });
}

void runPrepare(PrepareOptions o) {
  const std::optional<PinholeCamera> inputCamera =
      o.camera.empty() ? cameraFromInput(o.input) : std::nullopt;
  const PinholeCamera camera = inputCamera ? *inputCamera : PinholeCamera::load(o.camera);
  const std::string cameraName =
      inputCamera ? "the sensor.yaml of '" + o.input + "'" : "camera file '" + o.camera + "'";
  MapExtenderParams extenderParams;
  UnpreparedMapParams unpreparedParams;
  if (o.unprepared) loadUnpreparedParams(o.params, extenderParams, unpreparedParams);
  const ReferencePreparerParams params = o.unprepared ? extenderParams.preparation
                                         : o.params.empty()
                                             ? ReferencePreparerParams{}
                                             : ReferencePreparerParams::load(o.params);
  std::vector<ReferenceImage> images;
  std::vector<double> timestamps;
  if (!o.input.empty()) {
    SequenceReferences refs = readSequenceReferences(o);
    images = std::move(refs.images);
    o.images = std::move(refs.names);
    timestamps = std::move(refs.timestamps);
  } else {
    for (const std::string& path : o.images) images.push_back(readReferenceImage(path));
  }
  for (const ReferenceImage& r : images) {
    if (r.image.size() != camera.imageSize())
      throw Error("reference image '" + r.name + "' is " + std::to_string(r.image.cols) + "x" +
                  std::to_string(r.image.rows) + " but " + cameraName + " is for " +
                  std::to_string(camera.imageSize().width) + "x" +
                  std::to_string(camera.imageSize().height) + " images");
  }
  const MultiReferencePreparer preparer(camera, params);
  const auto progress = [&](const ReferencePairReport& r) { printPair(r, o.images); };
  std::optional<MultiPreparation> prepared;
  if (o.unprepared) {
    const MetricScale scale =
        o.baseline > 0.0
            ? MetricScale::baseline(o.baseline)
            : MetricScale::distance(o.distance, {o.distancePoints[0], o.distancePoints[1]},
                                    {o.distancePoints[2], o.distancePoints[3]});
    extenderParams.tracker.mode = TrackingMode::SixDof;
    const UnpreparedInitializer initializer(camera, extenderParams, unpreparedParams);
    UnpreparedMap built = initializer.build(
        images, scale,
        [](const std::string& step) { std::printf("unprepared: %s\n", step.c_str()); }, progress);
    printUnprepared(built.report);
    prepared = std::move(built.prepared);
    // The references added after the first two, in the summary's per-reference lines.
    MultiPreparationReport& r = prepared->report;
    for (std::size_t v = r.corners.size(); v < prepared->map.views.size(); ++v) {
      r.corners.push_back(static_cast<int>(prepared->map.views[v].corners.size()));
      r.markerRmsPx.push_back(std::nullopt);
    }
    r.observationHistogram.assign(prepared->map.views.size() + 1, 0);
    for (const MapPoint& p : prepared->map.points) ++r.observationHistogram[p.observations.size()];
  } else if (!o.marker.empty()) {
    prepared = preparer.prepare(images, MarkerSpec::parse(o.marker), progress);
  } else if (!o.input.empty()) {
    // The ground-truth pose at each reference frame's timestamp (interpolated).
    const GroundTruth gt = loadGroundTruth(o.poses, kMaxGroundTruthGap);
    std::printf("reference poses: %s\n", gt.description.c_str());
    std::vector<RigidPose> T;
    for (std::size_t i = 0; i < images.size(); ++i) {
      const TumTrajectory at =
          interpolateTrajectory(gt.trajectory, {timestamps[i]}, kMaxGroundTruthGap);
      if (at.poses.empty())
        throw Error("reference frame " + std::to_string(o.refFrames[i]) +
                    " (t = " + std::to_string(timestamps[i]) + " s) has no ground-truth pose in '" +
                    o.poses + "' (outside it, or in a gap longer than " +
                    std::to_string(kMaxGroundTruthGap) + " s)");
      T.push_back(at.poses.front().worldToCamera);
    }
    prepared = preparer.prepare(images, T, "poses " + o.poses, progress);
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
      "matches merge into points seen by 2..N references. Writes OUT/map.yml (format version 3)\n"
      "and OUT/reference_00.png, reference_01.png, ...\n"
      "From a recorded sequence: --input SRC --ref-frames I,J,... takes the references from\n"
      "SRC (e.g. tum:DIR or euroc:DIR) and --poses the ground truth at their timestamps\n"
      "(a TUM file, tum:DIR or euroc:DIR, interpolated); euroc: inputs bring their camera.\n"
      "No marker, no poses (--unprepared): the first two references' relative pose comes from\n"
      "their own keypoint matches (essential matrix), refined from their corner matches; the\n"
      "world lies on the scene's dominant plane (origin at its centre, z toward the cameras, x\n"
      "along the first camera's x), and one length you know gives the metres: --baseline M (how\n"
      "far the camera moved between the two) or --distance M --distance-points X1,Y1,X2,Y2 (two\n"
      "points of the plane marked in the first reference). A pure rotation, too little parallax\n"
      "or a textureless view is refused with what to do. Further references are located in that\n"
      "map and added as `extend` adds them.");
  CLI::Option* cameraOption =
      sub->add_option("--camera", options->camera,
                      "camera file (camera.yml; default for euroc: inputs: their sensor.yaml)")
          ->check(CLI::ExistingFile);
  CLI::Option* input = sub->add_option(
      "--input", options->input,
      "a sequence (video, image folder, tum:DIR, euroc:DIR) holding the references");
  CLI::Option* refFrames =
      sub->add_option("--ref-frames", options->refFrames,
                      "with --input: the frame indices that become references (N >= 2)")
          ->delimiter(',')
          ->check(CLI::NonNegativeNumber);
  input->needs(refFrames);
  refFrames->needs(input);
  CLI::Option* ref = sub->add_option("--ref", options->refs, "reference image (repeat: N >= 2)")
                         ->check(CLI::ExistingFile);
  CLI::Option* refs =
      sub->add_option("--refs", options->refsFolder, "folder of reference images (sorted by name)")
          ->check(CLI::ExistingDirectory);
  CLI::Option* refA =
      sub->add_option("--ref-a", options->refA, "reference image A")->check(CLI::ExistingFile);
  CLI::Option* refB =
      sub->add_option("--ref-b", options->refB, "reference image B")->check(CLI::ExistingFile);
  ref->excludes(refs)->excludes(refA)->excludes(refB)->excludes(input);
  refs->excludes(input);
  refA->excludes(input);
  refs->excludes(ref)->excludes(refA)->excludes(refB);
  refA->needs(refB);
  refB->needs(refA);
  CLI::Option* marker = sub->add_option("--marker", options->marker,
                                        "marker DICT:ID:SIDE_M, e.g. DICT_6X6_250:23:0.2")
                            ->check(parsingValidator<MarkerSpec>("MARKER"));
  CLI::Option* poses =
      sub->add_option(
             "--poses", options->poses,
             "TUM file with one pose per reference, in order (--ref-a/--ref-b: first two); "
             "with --input: a TUM file, tum:DIR or euroc:DIR ground truth")
          ->check(CLI::Validator(
              [](std::string& v) -> std::string {
                return isDatasetSpec(v) ? std::string() : CLI::ExistingFile(v);
              },
              "FILE|tum:DIR|euroc:DIR"));
  marker->excludes(poses);
  poses->excludes(marker);
  CLI::Option* unprepared = sub->add_flag(
      "--unprepared", options->unprepared,
      "no marker, no poses: the references' poses from their own matches (the first two), the "
      "world on the scene's dominant plane, the scale from --baseline or --distance");
  CLI::Option* baseline =
      sub->add_option("--baseline", options->baseline,
                      "--unprepared: how far the camera moved between the first two references "
                      "(metres)")
          ->check(kPositiveMetres);
  CLI::Option* distance =
      sub->add_option("--distance", options->distance,
                      "--unprepared: the distance between the two --distance-points on the "
                      "scene's dominant plane (metres)")
          ->check(kPositiveMetres);
  CLI::Option* distancePoints =
      sub->add_option(
             "--distance-points", options->distancePoints,
             "--unprepared: X1,Y1,X2,Y2, two points of the first reference's image (pixels) "
             "on the scene's dominant plane, --distance apart")
          ->delimiter(',')
          ->expected(4)
          ->check(kFiniteNumber);
  unprepared->excludes(marker)->excludes(poses);
  baseline->needs(unprepared)->excludes(distance);
  distance->needs(unprepared)->needs(distancePoints);
  distancePoints->needs(distance);
  sub->add_option("--params", options->params,
                  "preparation parameters (YAML: corners, matching, marker, preparation; with "
                  "--unprepared also unprepared, extension, bundle_adjustment)")
      ->check(CLI::ExistingFile);
  sub->add_option("--out", options->out, "output folder of the reference map")->required();
  sub->callback([options, marker, poses, ref, refs, refA, input, cameraOption, unprepared, baseline,
                 distance] {
    PrepareOptions& o = *options;
    if (ref->count() == 0 && refs->count() == 0 && refA->count() == 0 && input->count() == 0)
      throw CLI::RequiredError("--ref (repeated), --refs, --ref-a/--ref-b or --input");
    if (unprepared->count() > 0 && baseline->count() == 0 && distance->count() == 0)
      throw CLI::RequiredError(
          "--unprepared needs the scale: --baseline M (how far the camera moved between the first "
          "two references) or --distance M with --distance-points X1,Y1,X2,Y2");
    if (unprepared->count() == 0 && marker->count() == 0 && poses->count() == 0)
      throw CLI::RequiredError("one of --marker, --poses or --unprepared");
    if (cameraOption->count() == 0 && o.input.rfind("euroc:", 0) != 0)
      throw CLI::RequiredError("--camera (only euroc: inputs bring their camera)");
    if (input->count() > 0) {
      if (o.refFrames.size() < 2)
        throw CLI::ValidationError(
            "--ref-frames",
            std::to_string(o.refFrames.size()) + " reference frame(s); at least 2 are needed");
      return;  // frames and poses are checked when read
    }
    if (poses->count() > 0 && isDatasetSpec(o.poses))
      throw CLI::ValidationError("--poses", "'" + o.poses +
                                                "' (a dataset's ground truth) needs --input and "
                                                "--ref-frames to pick the reference frames");
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
