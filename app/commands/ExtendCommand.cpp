// `reftrack extend`: grows a reference map from a video (issue 13). Tracks the video in 6-DOF,
// adds a reference wherever a well-supported frame leaves the volume the references cover,
// matches it to the references it overlaps, bundle-adjusts the added references and the points
// with the anchored references fixed (MapExtender, ReferenceBundleAdjuster), and writes the
// extended map (MultiReferenceMap::save, atomic).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "app/cli/ProgressBar.hpp"
#include "app/commands/Commands.hpp"
#include "app/sources/FrameSourceFactory.hpp"
#include "engine/config/ConfigValue.hpp"
#include "engine/core/Error.hpp"
#include "engine/mapping/MapExtender.hpp"
#include "engine/relocalisation/ReferenceKeypointBuilder.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {

namespace {

struct ExtendOptions {
  std::string map, input, out, params, extendParams;
  int frames = -1;
};

MapExtenderParams loadParams(const ExtendOptions& o) {
  MapExtenderParams p;
  if (!o.params.empty()) p.tracker = TrackerParams::load(o.params);
  p.tracker.mode = TrackingMode::SixDof;
  if (!o.extendParams.empty())
    readParameterFile(o.extendParams, [&](const cv::FileNode& root) {
      p.extension.read(root["extension"]);
      p.bundleAdjustment.read(root["bundle_adjustment"]);
      p.preparation.read(root, {"extension", "bundle_adjustment"});
    });
  p.check();
  return p;
}

std::string viewList(const std::vector<int>& views) {
  std::string s;
  for (int v : views) s += (s.empty() ? "" : ", ") + std::to_string(v);
  return s.empty() ? "none" : s;
}

void printAdjustment(const char* what, const BundleAdjustmentReport& r) {
  std::printf(
      "%s: %d references refined, %d held, %d points, %d observations (%d outliers > threshold): "
      "RMS %.3f -> %.3f px, %d iterations%s\n",
      what, r.viewsRefined, r.viewsHeld, r.pointsRefined, r.observations, r.outliers,
      r.initialRmsPx, r.finalRmsPx, r.iterations, r.converged ? "" : " (did not converge)");
}

void printSummary(const MapExtender& extender, const MultiReferenceMap& before, int frames,
                  int tracked, int wellSupported, const std::vector<std::string>& rejections,
                  const BundleAdjustmentReport& final, const MapExtenderParams& p,
                  const std::string& out) {
  const MultiReferenceMap& map = extender.map();
  std::printf("extend: %d frames, %d tracked (%.1f%%), %d well supported\n", frames, tracked,
              100.0 * tracked / frames, wellSupported);
  std::printf("references: %d -> %d (%zu added); map points: %zu -> %zu\n", before.size(),
              map.size(), extender.added().size(), before.points.size(), map.points.size());
  for (const AddedReference& a : extender.added()) {
    const ReferenceView& v = map.views[static_cast<std::size_t>(a.view)];
    if (a.reason == ExtensionReason::Distance)
      std::printf("  reference %d (%s) from frame %d: distance %.3f m to reference %d (> %.3f m)",
                  a.view, v.name.c_str(), a.frameIndex, a.distanceMetres, a.nearestView,
                  p.extension.maxDistanceMetres);
    else
      std::printf(
          "  reference %d (%s) from frame %d: angle %.1f deg to the references within "
          "%.3f m (> %.1f deg)",
          a.view, v.name.c_str(), a.frameIndex, a.angleDeg, p.extension.maxDistanceMetres,
          p.extension.maxAngleDeg);
    std::printf("; matched to %s: %d points extended, %d added; BA RMS %.3f -> %.3f px\n",
                viewList(a.matchedViews).c_str(), a.pointsExtended, a.pointsAdded,
                a.adjustment.initialRmsPx, a.adjustment.finalRmsPx);
  }
  for (const std::string& r : rejections) std::printf("  not added: %s\n", r.c_str());
  printAdjustment("final bundle adjustment", final);
  for (std::size_t i = 0; i < map.views.size(); ++i) {
    const ViewAdjustment& v = final.views[i];
    std::printf("  reference %zu %s: %d observations, RMS %.3f -> %.3f px%s\n", i,
                v.anchored ? "anchored" : (v.refined ? "refined " : "held    "), v.observations,
                v.initialRmsPx, v.finalRmsPx, v.outliers ? " (with outliers)" : "");
  }
  std::printf("wrote %s\n", out.c_str());
}

void runExtend(const ExtendOptions& o) {
  const MapExtenderParams params = loadParams(o);
  const MultiReferenceMap before = MultiReferenceMap::load(o.map);
  MapExtender extender(before, params);

  std::unique_ptr<render::GlContext> gl;
  if (isSimulatorInput(o.input)) gl = render::createHeadlessContext();
  FrameSourceOptions sourceOptions;
  sourceOptions.simSize = before.camera.imageSize();
  std::unique_ptr<FrameSource> source = openFrameSource(o.input, sourceOptions);
  const int total = o.frames > 0 ? std::min(o.frames, source->frameCount().value_or(o.frames))
                                 : source->frameCount().value_or(0);
  ProgressBar progress("extend", static_cast<std::size_t>(std::max(total, 0)));
  int processed = 0, tracked = 0, wellSupported = 0;
  std::vector<std::string> rejections;
  while (o.frames < 0 || processed < o.frames) {
    std::optional<Frame> frame = source->next();
    if (!frame) break;
    if (frame->image.size() != before.camera.imageSize())
      throw Error("frame " + std::to_string(frame->index) + " of '" + o.input + "' is " +
                  std::to_string(frame->image.cols) + "x" + std::to_string(frame->image.rows) +
                  " but the map's camera is for " +
                  std::to_string(before.camera.imageSize().width) + "x" +
                  std::to_string(before.camera.imageSize().height) + " images");
    const ExtensionFrame f = extender.process(frame->image, frame->index);
    if (f.tracking.worldToCamera) ++tracked;
    if (f.wellSupported) ++wellSupported;
    if (!f.rejected.empty() && rejections.size() < 10)
      rejections.push_back("frame " + std::to_string(frame->index) + ": " + f.rejected);
    ++processed;
    progress.advance();
  }
  progress.finish();
  if (processed == 0) throw Error("input '" + o.input + "' gave no frames");
  const BundleAdjustmentReport final = extender.finish();
  // The keypoint layer of every reference (relocalisation), as `prepare` builds it.
  if (params.tracker.relocalisation.enabled) {
    buildReferenceKeypoints(extender.map(), params.tracker.relocalisation);
    std::size_t keypoints = 0, withPoints = 0;
    for (const ReferenceView& v : extender.map().views) {
      keypoints += v.keypoints.keypoints.size();
      for (const Eigen::Vector3d& X : v.keypoints.points) withPoints += X.allFinite() ? 1 : 0;
    }
    std::printf("keypoint layer (%s): %zu keypoints over %d references, %zu with a 3D point\n",
                extender.map().keypointKind.c_str(), keypoints, extender.map().size(), withPoints);
  }
  extender.map().save(o.out);
  printSummary(extender, before, processed, tracked, wellSupported, rejections, final, params,
               o.out);
}

CommandRegistration registerExtendCommand(CLI::App& parent) {
  auto options = std::make_shared<ExtendOptions>();
  CLI::App* sub = parent.add_subcommand(
      "extend", "Grow a reference map from a video: add references where the camera leaves it");
  sub->footer(
      "The first frame must be near reference 0 (or the reference sharing most points with it).\n"
      "A tracked frame farther than extension.max_distance_m from every reference, or turned more\n"
      "than extension.max_angle_deg from the references near it, becomes a new reference\n"
      "(anchored: false); a bundle adjustment refines the added references and the points with\n"
      "the given (anchored) references fixed. --extend-params YAML sections: extension,\n"
      "bundle_adjustment, and the preparation's corners and matching.");
  sub->add_option("--map", options->map, "reference map folder (prepare or extend output)")
      ->required()
      ->check(CLI::ExistingDirectory);
  sub->add_option("--input", options->input, "video file, image folder or glob, or sim:PRESET")
      ->required();
  sub->add_option("--out", options->out, "output folder of the extended map")->required();
  sub->add_option("--params", options->params, "TrackerParams YAML (as `track --params`)")
      ->check(CLI::ExistingFile);
  sub->add_option("--extend-params", options->extendParams,
                  "extension parameters YAML (extension, bundle_adjustment, corners, matching)")
      ->check(CLI::ExistingFile);
  sub->add_option("--frames", options->frames, "process at most N frames")
      ->check(CLI::Range(1, 100000000));
  return {sub, [options] { runExtend(*options); }};
}

const CommandRegistrar registrar(37, registerExtendCommand);

}  // namespace

}  // namespace reftrack::app
