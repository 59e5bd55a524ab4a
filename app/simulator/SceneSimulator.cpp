#include "app/simulator/SceneSimulator.hpp"

#include "app/simulator/CameraEffectsPipeline.hpp"
#include "app/simulator/DeskScene.hpp"
#include "app/simulator/DistortingLens.hpp"
#include "app/simulator/PhotoPrints.hpp"
#include "app/simulator/ReferencePlacement.hpp"
#include "app/simulator/SensorNoise.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/LookAt.hpp"
#include "render/CameraProjection.hpp"

namespace reftrack::app {

namespace {
constexpr int kSupersample = 3;
constexpr int kBlurSubframes = 5;
const cv::Scalar kBackgroundBgr(70, 70, 70);  // beyond the desk and walls
// Noise streams of the reference images, apart from every frame index.
constexpr std::uint64_t kReferenceStream = 0x5245464552454E43ull;
}  // namespace

SceneSimulator::SceneSimulator(SimulationOptions options) : options_(std::move(options)) {
  options_.check();
  camera_ = PinholeCamera::fromFieldOfView(options_.size, options_.fovDeg);
  if (!options_.distortion.empty()) {
    camera_ = PinholeCamera(camera_.K(), camera_.imageSize(), options_.distortion);
    if (camera_.hasDistortion()) lens_ = std::make_unique<DistortingLens>(camera_, kSupersample);
  }
  DeskScene scene = buildDeskScene();
  if (options_.referenceBaseline > 0.0)
    scene.referenceEyeB =
        scene.referenceEyeA +
        options_.referenceBaseline * (scene.referenceEyeB - scene.referenceEyeA).normalized();
  marker_ = scene.marker;
  lookedAt_ = scene.contentCentre;
  references_ = placeReferenceViews(options_.referenceCount(), scene.referenceEyeA,
                                    scene.referenceEyeB, scene.contentCentre);
  path_ = std::make_unique<CameraPath>(options_, scene.referenceEyeA, scene.contentCentre);
  renderer_ = std::make_unique<render::SceneRenderer>();
  for (const render::TexturedMesh& mesh : scene.meshes) renderer_->addMesh(mesh);
  if (options_.effects.photos)
    for (const render::TexturedMesh& mesh : photoPrintMeshes(options_.effects.photoFile))
      renderer_->addMesh(mesh);
  if (options_.effects.any()) {
    CameraEffects effects = options_.effects;
    if (options_.blur && effects.exposureMs == 0.0) effects.exposureMs = 1000.0 / options_.fps;
    effects_ = std::make_unique<CameraEffectsPipeline>(
        effects,
        CameraSetup{options_.size, options_.fps, options_.frames, options_.seed,
                    options_.noiseSigma},
        [this](double frameTime) {
          const RigidPose pose = path_->at(frameTime);
          // Through a lens the ideal image is resampled at the lens's fixed 3x supersampling.
          if (lens_) return renderClean(pose);
          // Several renders per frame average into one: 2x supersampling each (measured: a
          // render costs ~(supersample)^2), the time average smooths what it leaves.
          const int supersample = effects_->timeSamples() > 1 ? 2 : kSupersample;
          return renderer_->render(view(pose), supersample, nullptr, kBackgroundBgr);
        });
  }
}

SceneSimulator::~SceneSimulator() = default;

RigidPose SceneSimulator::framePose(int k) const {
  if (k < 0 || k >= options_.frames)
    throw Error("simulated frame " + std::to_string(k) + " is outside 0.." +
                std::to_string(options_.frames - 1));
  return path_->at(k);
}

render::PinholeView SceneSimulator::view(const RigidPose& worldToCamera) const {
  if (!worldToCamera.allFinite()) throw Error("simulator: camera pose contains NaN or infinity");
  render::PinholeView v;
  v.K = camera_.K();
  v.imageSize = camera_.imageSize();
  v.worldToCamera = worldToCamera.matrix4();
  v.nearPlane = 0.02;
  v.farPlane = 20.0;
  return v;
}

render::PinholeView SceneSimulator::idealView(const RigidPose& worldToCamera, int scale) const {
  render::PinholeView v = view(worldToCamera);
  v.K = render::supersampledK(lens_->idealK(), scale);
  v.imageSize = cv::Size(lens_->idealSize().width * scale, lens_->idealSize().height * scale);
  return v;
}

cv::Mat SceneSimulator::renderClean(const RigidPose& worldToCamera) {
  if (!lens_) return renderer_->render(view(worldToCamera), kSupersample, nullptr, kBackgroundBgr);
  // Through the lens: the ideal image, supersampled, resampled where the lens puts each pixel.
  const cv::Mat ideal =
      renderer_->render(idealView(worldToCamera, kSupersample), 1, nullptr, kBackgroundBgr);
  return lens_->distortSupersampled(ideal);
}

cv::Mat SceneSimulator::renderView(const RigidPose& worldToCamera, std::uint64_t noiseSeed,
                                   double noiseSigma) {
  return addSensorNoise(renderClean(worldToCamera), noiseSeed, noiseSigma);
}

cv::Mat SceneSimulator::renderFrame(int k) {
  const RigidPose pose = framePose(k);
  const std::uint64_t seed = mixSeed(options_.seed, static_cast<std::uint64_t>(k));
  if (effects_) return effects_->frame(k);
  if (!options_.blur) return renderView(pose, seed, options_.noiseSigma);
  cv::Mat sum(camera_.imageSize(), CV_32FC3, cv::Scalar::all(0));
  for (int i = 0; i < kBlurSubframes; ++i) {
    const double s = k - 0.5 + (i + 0.5) / kBlurSubframes;
    cv::Mat sub;
    renderClean(path_->at(s)).convertTo(sub, CV_32FC3);
    sum += sub;
  }
  return addSensorNoise(sum / kBlurSubframes, seed, options_.noiseSigma);
}

cv::Mat SceneSimulator::renderReference(char which) {
  if (which != 'A' && which != 'B')
    throw Error(std::string("simulator: reference view must be 'A' or 'B', got '") + which + "'");
  return renderReferenceView(which == 'A' ? 0 : 1);
}

cv::Mat SceneSimulator::renderReferenceView(int index) {
  const int count = static_cast<int>(references_.size());
  if (index < 0 || index >= count)
    throw Error("simulator: reference view " + std::to_string(index) + " is outside 0.." +
                std::to_string(count - 1));
  // Views A and B keep the noise streams they always had ('A', 'B'); the others follow on.
  const std::uint64_t stream =
      index < 2 ? static_cast<std::uint64_t>(index == 0 ? 'A' : 'B') : 256u + index;
  const RigidPose& pose = references_[static_cast<std::size_t>(index)];
  const std::uint64_t seed = mixSeed(mixSeed(options_.seed, kReferenceStream), stream);
  if (effects_) return effects_->still(renderClean(pose), seed);
  return renderView(pose, seed, options_.noiseSigma);
}

cv::Mat SceneSimulator::renderDepth(const RigidPose& worldToCamera) {
  // No supersampling: each pixel's depth is that of the surface at its centre, not a blend of
  // surfaces across an edge.
  cv::Mat depth;
  if (!lens_) {
    renderer_->render(view(worldToCamera), 1, &depth, kBackgroundBgr);
    return depth;
  }
  renderer_->render(idealView(worldToCamera, 1), 1, &depth, kBackgroundBgr);
  return lens_->distortDepth(depth);
}

}  // namespace reftrack::app
