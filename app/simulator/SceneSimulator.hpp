#pragma once
// SceneSimulator: renders the fixed desk scene (DeskScene) along a camera path (CameraPath) with
// exact ground truth. Images are rendered 3x supersampled (anti-aliased like a real camera), then
// get Gaussian sensor noise seeded from (seed, frame) — the same options give byte-identical
// frames. Renders with the GL context current on the calling thread; construct and use it there.
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>

#include "app/simulator/CameraPath.hpp"
#include "app/simulator/SimulationOptions.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/MarkerSpec.hpp"
#include "render/SceneRenderer.hpp"

namespace reftrack::app {

class SceneSimulator {
 public:
  explicit SceneSimulator(
      SimulationOptions options);  // builds scene + path; needs a current context
  ~SceneSimulator();
  SceneSimulator(const SceneSimulator&) = delete;
  SceneSimulator& operator=(const SceneSimulator&) = delete;

  const SimulationOptions& options() const { return options_; }
  const PinholeCamera& camera() const { return camera_; }
  const MarkerSpec& marker() const { return marker_; }      // DICT_6X6_250, id 23, side 0.2 m
  RigidPose referencePoseA() const { return referenceA_; }  // world->camera
  RigidPose referencePoseB() const { return referenceB_; }
  RigidPose framePose(
      int k) const;  // world->camera, exact ground truth; throws outside 0..frames-1

  // BGR, noise (+ motion blur: the mean of 5 renders over [k - 1/2, k + 1/2]) per options;
  // deterministic in (seed, k).
  cv::Mat renderFrame(int k);
  cv::Mat renderReference(char which);  // 'A' or 'B' (with sensor noise)
  cv::Mat renderView(const RigidPose& worldToCamera, std::uint64_t noiseSeed, double noiseSigma);
  cv::Mat renderDepth(const RigidPose& worldToCamera);  // CV_32F camera z in metres (true surface)

 private:
  render::PinholeView view(const RigidPose& worldToCamera) const;
  cv::Mat renderClean(const RigidPose& worldToCamera);  // CV_8UC3, no noise

  SimulationOptions options_;
  PinholeCamera camera_;
  MarkerSpec marker_;
  RigidPose referenceA_, referenceB_;
  std::unique_ptr<CameraPath> path_;
  std::unique_ptr<render::SceneRenderer> renderer_;
};

}  // namespace reftrack::app
