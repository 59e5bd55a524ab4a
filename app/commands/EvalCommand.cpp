// `reftrack eval`: accuracy of an estimated trajectory against ground truth (ATE, RPE, cube
// reprojection error, jitter, tracked fraction), as text or one JSON object, plus PNG plots.
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "app/commands/Commands.hpp"
#include "app/plot/PlotCanvas.hpp"
#include "engine/core/Error.hpp"
#include "engine/dataset/DatasetGroundTruth.hpp"
#include "engine/evaluation/TrajectoryEvaluator.hpp"
#include "engine/evaluation/TrajectoryInterpolation.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack::app {

namespace {

struct EvalOptions {
  std::string gt, est, camera, plotDir, align = "none";
  // --anchor-map: the estimate's world is this map's, whose reference 0 was taken at
  // anchorTime of the ground truth; --cube-ahead: the cube centred that far in front of it.
  std::string anchorMap;
  double anchorTime = 0.0, cubeAhead = 0.0;
  std::vector<double> cubeAt;
  bool json = false, noPlots = false;
  double maxGap = 0.05;  // s; ground-truth samples farther apart are not interpolated
  EvaluationParams params;
};

std::string number(double v);

std::string alignmentText(const TrajectoryEvaluation& ev, const EvalOptions& o) {
  if (!o.anchorMap.empty())
    return "anchored: the map '" + o.anchorMap + "' carried into the ground truth's world by " +
           "its reference 0, at the truth's pose of t = " + number(o.anchorTime) + " s";
  if (!ev.aligned)
    return "none (the default; --align se3|sim3|se3-views aligns the estimate first)";
  char scale[64];
  std::snprintf(scale, sizeof scale, ", scale %.6g", ev.alignmentScale);
  return o.align +
         (o.params.alignment == TrajectoryAlignment::Se3Views
              ? " (Umeyama least squares on the camera centres and three points of each view"
              : " (Umeyama least squares on the camera centres") +
         (o.params.alignment == TrajectoryAlignment::Sim3 ? std::string(scale) : "") + ")";
}

std::string number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string statsJson(const ErrorStats& s) {
  return "{\"count\": " + std::to_string(s.count) + ", \"rmse\": " + number(s.rmse) +
         ", \"mean\": " + number(s.mean) + ", \"median\": " + number(s.median) +
         ", \"p95\": " + number(s.p95) + ", \"max\": " + number(s.max) + "}";
}

std::string toJson(const TrajectoryEvaluation& ev, const EvalOptions& o,
                   const std::string& gtDescription, const std::vector<std::string>& plots) {
  std::ostringstream j;
  j << "{\"ground_truth\": " << jsonString(o.gt)
    << ", \"ground_truth_source\": " << jsonString(gtDescription)
    << ", \"estimate\": " << jsonString(o.est)
    << ", \"ground_truth_frames\": " << ev.groundTruthFrames
    << ", \"estimate_frames\": " << ev.estimateFrames
    << ", \"associated_frames\": " << ev.associatedFrames
    << ", \"tracked_fraction\": " << number(ev.trackedFraction)
    << ", \"aligned\": " << (ev.aligned ? "true" : "false")
    << ", \"alignment\": " << jsonString(o.align)
    << ", \"alignment_scale\": " << number(ev.alignmentScale)
    << ", \"ate_translation_mm\": " << statsJson(ev.ateTranslationMm)
    << ", \"ate_rotation_deg\": " << statsJson(ev.ateRotationDeg)
    << ", \"rpe_translation_mm\": " << statsJson(ev.rpeTranslationMm)
    << ", \"rpe_rotation_deg\": " << statsJson(ev.rpeRotationDeg)
    << ", \"cube_side_m\": " << number(o.params.cubeSide)
    << ", \"cube_error_px\": " << (ev.cubeErrorPx ? statsJson(*ev.cubeErrorPx) : "null")
    << ", \"jitter_mm\": " << (ev.jitterMm ? number(*ev.jitterMm) : "null")
    << ", \"jitter_px\": " << (ev.jitterPx ? number(*ev.jitterPx) : "null") << ", \"plots\": [";
  for (std::size_t i = 0; i < plots.size(); ++i) j << (i ? ", " : "") << jsonString(plots[i]);
  j << "]}";
  return j.str();
}

void printText(const TrajectoryEvaluation& ev, const EvalOptions& o,
               const std::string& gtDescription) {
  auto line = [](const char* name, const ErrorStats& s, const char* unit) {
    std::printf("%-22s rmse %9.3f  mean %9.3f  median %9.3f  p95 %9.3f  max %9.3f  %s\n", name,
                s.rmse, s.mean, s.median, s.p95, s.max, unit);
  };
  std::printf("ground truth: %s\n", gtDescription.c_str());
  std::printf("alignment: %s\n", alignmentText(ev, o).c_str());
  std::printf(
      "frames: %zu ground truth, %zu estimated, %zu associated (within %g s); tracked %.1f%%\n",
      ev.groundTruthFrames, ev.estimateFrames, ev.associatedFrames, o.params.maxTimeDifference,
      100.0 * ev.trackedFraction);
  line("ATE translation", ev.ateTranslationMm, "mm");
  line("ATE rotation", ev.ateRotationDeg, "deg");
  line("RPE translation/frame", ev.rpeTranslationMm, "mm");
  line("RPE rotation/frame", ev.rpeRotationDeg, "deg");
  if (ev.cubeErrorPx)
    std::printf(
        "cube (%.3f m) vertex reprojection error: mean %.3f px, 95th percentile %.3f px, "
        "max %.3f px\n",
        o.params.cubeSide, ev.cubeErrorPx->mean, ev.cubeErrorPx->p95, ev.cubeErrorPx->max);
  else
    std::printf("cube vertex reprojection error: needs --camera\n");
  if (ev.jitterMm)
    std::printf("jitter (cube vertices, second differences): %.3f mm%s\n", *ev.jitterMm,
                ev.jitterPx ? (", " + number(*ev.jitterPx) + " px").c_str() : "");
  else
    std::printf("jitter: needs three consecutive tracked frames\n");
}

std::vector<std::string> writePlots(const TrajectoryEvaluation& ev, const EvalOptions& o) {
  namespace fs = std::filesystem;
  const fs::path est(o.est);
  const fs::path dir =
      o.plotDir.empty() ? (est.has_parent_path() ? est.parent_path() : ".") : fs::path(o.plotDir);
  if (!fs::is_directory(dir)) throw Error("plot folder '" + dir.string() + "' does not exist");
  const std::string stem = est.stem().string();
  std::vector<double> t, ate, rot, cube, gx, gy, ex, ey;
  for (const FrameEvaluation& f : ev.frames) {
    t.push_back(f.timestamp - ev.frames.front().timestamp);
    ate.push_back(f.translationErrorMm);
    rot.push_back(f.rotationErrorDeg);
    cube.push_back(f.cubeErrorPx.value_or(std::nan("")));
    gx.push_back(f.trueCentre.x()), gy.push_back(f.trueCentre.y());
    ex.push_back(f.estimatedCentre.x()), ey.push_back(f.estimatedCentre.y());
  }
  std::vector<std::string> written;
  PlotCanvas error("Error over time: " + stem, "time (s)", "error");
  error.addLine("ATE translation (mm)", t, ate, cv::Scalar(200, 80, 0));
  error.addLine("ATE rotation (deg)", t, rot, cv::Scalar(0, 140, 0));
  if (ev.cubeErrorPx) error.addLine("cube vertices (px)", t, cube, cv::Scalar(0, 0, 220));
  const fs::path errorPng = dir / (stem + ".error.png");
  error.save(errorPng);
  written.push_back(errorPng.string());

  PlotCanvas top("Camera centres, top view: " + stem, "x (m)", "y (m)");
  top.setEqualAspect(true);
  top.addLine("ground truth", gx, gy, cv::Scalar(60, 60, 60));
  top.addScatter("estimate", ex, ey, cv::Scalar(0, 0, 220));
  top.addScatter("marker", {0.0}, {0.0}, cv::Scalar(200, 80, 0));
  const fs::path topPng = dir / (stem + ".topview.png");
  top.save(topPng);
  written.push_back(topPng.string());
  return written;
}

// Carries the estimate from the map's world into the ground truth's by the map's reference 0:
// X_gt = T0_gt^-1 T0_map X_map (T0_gt the truth at the anchor time), so each estimated pose is
// compared with the truth as seen from reference 0's view, whatever world the map chose.
// With --cube-ahead, the cube is centred that far along reference 0's optical axis.
void anchorToMap(const GroundTruth& gt, TumTrajectory& est, EvalOptions& o) {
  if (o.anchorMap.empty()) return;
  const MultiReferenceMap map = MultiReferenceMap::load(o.anchorMap);
  const TumTrajectory at = interpolateTrajectory(gt.trajectory, {o.anchorTime}, o.maxGap);
  if (at.poses.empty())
    throw Error("--anchor-time " + number(o.anchorTime) + ": the ground truth has no pose there");
  const RigidPose truth0 = at.poses.front().worldToCamera;
  const RigidPose mapToTruth = truth0.inverse() * map.views.front().T;
  const RigidPose truthToMap = mapToTruth.inverse();
  for (StampedPose& p : est.poses) p.worldToCamera = p.worldToCamera * truthToMap;
  if (o.cubeAhead > 0.0)
    o.params.cubeBase = truth0.inverse() * Eigen::Vector3d(0.0, 0.0, o.cubeAhead) -
                        Eigen::Vector3d(0.0, 0.0, 0.5 * o.params.cubeSide);
}

void runEval(EvalOptions o) {
  o.params.alignment = parseTrajectoryAlignment(o.align);
  if (o.cubeAt.size() == 3) o.params.cubeBase = {o.cubeAt[0], o.cubeAt[1], o.cubeAt[2]};
  const GroundTruth gt = loadGroundTruth(o.gt, o.maxGap);
  TumTrajectory est = TumTrajectory::load(o.est);
  anchorToMap(gt, est, o);
  std::unique_ptr<PinholeCamera> camera;
  if (!o.camera.empty()) camera = std::make_unique<PinholeCamera>(PinholeCamera::load(o.camera));
  const TrajectoryEvaluation ev = evaluateTrajectory(gt.trajectory, est, o.params, camera.get());
  std::vector<std::string> plots;
  if (!o.noPlots) plots = writePlots(ev, o);
  if (o.json) {
    std::printf("%s\n", toJson(ev, o, gt.description, plots).c_str());
    return;
  }
  printText(ev, o, gt.description);
  for (const std::string& p : plots) std::printf("wrote %s\n", p.c_str());
}

CommandRegistration registerEvalCommand(CLI::App& parent) {
  auto options = std::make_shared<EvalOptions>();
  CLI::App* sub = parent.add_subcommand(
      "eval", "Compare an estimated trajectory with ground truth (ATE, RPE, cube error, jitter)");
  sub->add_option("--gt", options->gt,
                  "ground truth: a TUM trajectory file, tum:DIR (TUM RGB-D groundtruth.txt at the "
                  "rgb.txt frame times) or euroc:DIR (EuRoC state_groundtruth_estimate0 through "
                  "cam0's T_BS, at the cam0 frame times)")
      ->required()
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            if (v.rfind("tum:", 0) == 0 || v.rfind("euroc:", 0) == 0) return "";
            return CLI::ExistingFile(v);
          },
          "FILE|tum:DIR|euroc:DIR"));
  sub->add_option("--est", options->est, "estimated trajectory (TUM)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--camera", options->camera, "camera.yml: enables the cube reprojection error")
      ->check(CLI::ExistingFile);
  sub->add_option("--cube", options->params.cubeSide, "side of the virtual cube (m)")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 1e3));
  sub->add_option("--max-dt", options->params.maxTimeDifference,
                  "largest timestamp difference for association (s)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  sub->add_option("--max-gap", options->maxGap,
                  "tum:/euroc: ground truth: largest gap between two samples to interpolate "
                  "across (s)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  sub->add_option("--align", options->align,
                  "align the estimate to the ground truth first (Umeyama on the camera centres): "
                  "none, se3 (rigid) or sim3 (rigid + scale); se3-views: rigid, on the centres "
                  "and three points of each camera's view (orientations count too)")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "se3", "sim3", "se3-views"}));
  CLI::Option* cubeAt =
      sub->add_option("--cube-at", options->cubeAt,
                      "X,Y,Z: the centre of the cube's base (ground-truth world, m; default the "
                      "origin); it stands along world +z")
          ->delimiter(',')
          ->expected(3)
          ->check(CLI::Validator(
              [](std::string& v) -> std::string {
                double x = 0.0;
                return CLI::detail::lexical_cast(v, x) && std::isfinite(x)
                           ? ""
                           : "must be a finite number, got '" + v + "'";
              },
              "NUMBER"));
  CLI::Option* anchorMap =
      sub->add_option("--anchor-map", options->anchorMap,
                      "the map (folder) the estimate was tracked on: its world is carried into "
                      "the ground truth's by its reference 0 (X_gt = T0_gt^-1 T0_map X_map), no "
                      "fitted alignment; for maps in a world of their own (prepare --unprepared)")
          ->check(CLI::ExistingDirectory);
  CLI::Option* anchorTime =
      sub->add_option("--anchor-time", options->anchorTime,
                      "with --anchor-map: the ground-truth time (s) of reference 0's frame")
          ->check(CLI::Range(0.0, 1e12));
  CLI::Option* cubeAhead =
      sub->add_option("--cube-ahead", options->cubeAhead,
                      "with --anchor-map: the cube centred this far (m) along reference 0's "
                      "optical axis, its faces along the world axes")
          ->check(CLI::Range(1e-6, 1e6));
  anchorMap->needs(anchorTime);
  anchorTime->needs(anchorMap);
  cubeAhead->needs(anchorMap)->excludes(cubeAt);
  sub->add_flag("--json", options->json, "print one JSON object instead of text");
  sub->add_option("--plots", options->plotDir,
                  "folder for EST.error.png and EST.topview.png (default: beside --est)");
  sub->add_flag("--no-plots", options->noPlots, "write no plots");
  sub->callback([options, anchorMap] {
    if (anchorMap->count() > 0 && options->align != "none")
      throw CLI::ValidationError("--anchor-map",
                                 "the anchor fixes the alignment: give no --align with it");
  });
  return {sub, [options] { runEval(*options); }};
}

const CommandRegistrar registrar(60, registerEvalCommand);

}  // namespace

}  // namespace reftrack::app
