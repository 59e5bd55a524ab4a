#pragma once
// SceneSimulator: renders the fixed desk scene (DeskScene) along a camera path (CameraPath) with
// exact ground truth. Images are rendered 3x supersampled (anti-aliased like a real camera), then
// get Gaussian sensor noise seeded from (seed, frame) — the same options give byte-identical
// frames. With options.distortion the images are seen through that radial-tangential lens
// (DistortingLens: rendered on a larger ideal canvas and remapped; camera() carries the
// coefficients). Renders with the GL context current on the calling thread; construct and use it
// there.
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "app/simulator/CameraEffects.hpp"
#include "app/simulator/CameraPath.hpp"
#include "app/simulator/SimulationOptions.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/MarkerSpec.hpp"
#include "render/SceneRenderer.hpp"

namespace reftrack::app {

class CameraEffectsPipeline;
class DistortingLens;

class SceneSimulator {
 public:
  explicit SceneSimulator(
      SimulationOptions options);  // builds scene + path; needs a current context
  ~SceneSimulator();
  SceneSimulator(const SceneSimulator&) = delete;
  SceneSimulator& operator=(const SceneSimulator&) = delete;

  const SimulationOptions& options() const { return options_; }
  const PinholeCamera& camera() const { return camera_; }
  const MarkerSpec& marker() const { return marker_; }         // DICT_6X6_250, id 23, side 0.2 m
  RigidPose referencePoseA() const { return references_[0]; }  // world->camera
  RigidPose referencePoseB() const { return references_[1]; }
  // options.referenceCount() world->camera poses: A, B, then the views placeReferenceViews puts
  // on the walkaround arc.
  const std::vector<RigidPose>& referencePoses() const { return references_; }
  // The point every reference view and the camera paths look at (world frame).
  const Eigen::Vector3d& lookedAt() const { return lookedAt_; }
  RigidPose framePose(
      int k) const;  // world->camera, exact ground truth; throws outside 0..frames-1

  // BGR, noise (+ motion blur: the mean of 5 renders over [k - 1/2, k + 1/2]) per options;
  // deterministic in (seed, k). With options.effects on, CameraEffectsPipeline makes it (a
  // --blur without effects.exposureMs: a one-frame exposure); reference views then get its
  // still effects (defocus, vignetting, sensor noise). framePose(k) never changes.
  cv::Mat renderFrame(int k);
  cv::Mat renderReference(char which);  // 'A' or 'B' (with sensor noise)
  // Reference view `index` (0 = A, 1 = B, ...; with sensor noise); throws outside the range.
  cv::Mat renderReferenceView(int index);
  cv::Mat renderView(const RigidPose& worldToCamera, std::uint64_t noiseSeed, double noiseSigma);
  // CV_32F camera z in metres (true surface; through the lens: of the surface within 0.5 px).
  cv::Mat renderDepth(const RigidPose& worldToCamera);

 private:
  render::PinholeView view(const RigidPose& worldToCamera) const;
  // The lens's ideal canvas at `scale` times its size (lens_ only).
  render::PinholeView idealView(const RigidPose& worldToCamera, int scale) const;
  cv::Mat renderClean(const RigidPose& worldToCamera);  // CV_8UC3, no noise

  SimulationOptions options_;
  PinholeCamera camera_;
  MarkerSpec marker_;
  std::vector<RigidPose> references_;
  Eigen::Vector3d lookedAt_ = Eigen::Vector3d::Zero();
  std::unique_ptr<CameraPath> path_;
  std::unique_ptr<render::SceneRenderer> renderer_;
  std::unique_ptr<CameraEffectsPipeline> effects_;  // options.effects, when any is on
  std::unique_ptr<DistortingLens> lens_;            // null without distortion
};

}  // namespace reftrack::app
