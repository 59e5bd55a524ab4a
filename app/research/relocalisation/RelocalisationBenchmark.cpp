#include "app/research/relocalisation/RelocalisationBenchmark.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "app/research/baselines/OrbPnpColdStart.hpp"
#include "engine/core/Error.hpp"
#include "engine/core/ThreadCpuClock.hpp"
#include "engine/relocalisation/Relocaliser.hpp"

namespace reftrack::app {

namespace {

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * (v.size() - 1) + 0.5)];
}

void score(RelocalisationBenchmarkSide& side, const std::optional<RigidPose>& pose,
           const std::optional<RigidPose>& truth, const RelocalisationBenchmarkOptions& o) {
  if (!truth || !pose) return;
  ++side.found;
  const double mm = 1000.0 * (pose->cameraCentre() - truth->cameraCentre()).norm();
  const double deg = RigidPose::rotationDistance(*pose, *truth) * 180.0 / M_PI;
  side.centreErrorMm.push_back(mm);
  side.rotationErrorDeg.push_back(deg);
  if (mm > o.wrongCentreMm || deg > o.wrongRotationDeg) ++side.wrong;
}

}  // namespace

RelocalisationBenchmarkResult runRelocalisationBenchmark(
    const MultiReferenceMap& map, const std::vector<cv::Mat>& frames,
    const std::vector<std::optional<RigidPose>>& truth, const RelocalisationBenchmarkOptions& o) {
  if (truth.size() != frames.size())
    throw Error("relocalisation benchmark: " + std::to_string(truth.size()) + " poses for " +
                std::to_string(frames.size()) + " frames");
  const Relocaliser relocaliser(map, o.params);
  std::optional<MultiReferenceMap> orbMap;
  if (map.keypointKind != "orb") {
    orbMap = map;
    RelocalisationParams orb = o.params;
    orb.keypoints = "orb";
    buildReferenceKeypoints(*orbMap, orb);
  }
  OrbPnpColdStartParams baselineParams;
  baselineParams.minInliers = o.params.minInliers;
  const OrbPnpColdStart baseline(orbMap ? *orbMap : map, baselineParams);

  RelocalisationBenchmarkResult r;
  r.relocaliser.name = "relocaliser (" + o.params.keypoints + ")";
  r.baseline.name = "ORB + solvePnPRansac";
  for (std::size_t i = 0; i < frames.size(); ++i) {
    // Alternate which runs first, so neither always meets a warm or a cold cache.
    for (int turn = 0; turn < 2; ++turn) {
      const bool ours = (turn == 0) == (i % 2 == 0);
      const auto start = std::chrono::steady_clock::now();
      const double cpuStart = threadCpuMs();
      std::optional<RigidPose> pose;
      if (ours) {
        const RelocalisationAttempt a = relocaliser.locate(frames[i]);
        if (a.candidate) pose = a.candidate->worldToCamera;
      } else {
        pose = baseline.locate(frames[i]).worldToCamera;
      }
      const double cpuMs = threadCpuMs() - cpuStart;
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      RelocalisationBenchmarkSide& side = ours ? r.relocaliser : r.baseline;
      ++side.attempts;
      side.milliseconds.push_back(ms);
      side.cpuMilliseconds.push_back(cpuMs);
      score(side, pose, truth[i], o);
    }
  }
  r.medianMsRatio =
      quantile(r.relocaliser.milliseconds, 0.5) / quantile(r.baseline.milliseconds, 0.5);
  r.medianCpuMsRatio =
      quantile(r.relocaliser.cpuMilliseconds, 0.5) / quantile(r.baseline.cpuMilliseconds, 0.5);
  return r;
}

void printRelocalisationBenchmark(const RelocalisationBenchmarkResult& r, std::FILE* out) {
  std::fprintf(out, "  %-26s %9s %6s %9s %9s %10s %12s %12s\n", "method", "found", "wrong",
               "ms med", "ms p90", "cpu ms med", "centre mm", "rot deg");
  for (const RelocalisationBenchmarkSide* s : {&r.relocaliser, &r.baseline}) {
    const std::string found = std::to_string(s->found) + "/" + std::to_string(s->attempts);
    std::fprintf(out, "  %-26s %9s %6d %9.2f %9.2f %10.2f %12.2f %12.3f\n", s->name.c_str(),
                 found.c_str(), s->wrong, quantile(s->milliseconds, 0.5),
                 quantile(s->milliseconds, 0.9), quantile(s->cpuMilliseconds, 0.5),
                 quantile(s->centreErrorMm, 0.5), quantile(s->rotationErrorDeg, 0.5));
  }
  std::fprintf(out, "  median ms ratio (relocaliser / baseline): wall %.2f, thread CPU %.2f\n",
               r.medianMsRatio, r.medianCpuMsRatio);
}

}  // namespace reftrack::app
