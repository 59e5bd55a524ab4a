#include "app/viewer/TrackingPanel.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

bool inputDouble(const char* label, double& value, double step, const char* format) {
  return ImGui::InputDouble(label, &value, step, step * 10, format);
}

}  // namespace

void drawTrackingPanel(ViewerState& state, const cv::Rect2f& placement) {
  ImGui::SetNextWindowPos({placement.x, placement.y}, ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize({placement.width, placement.height}, ImGuiCond_FirstUseEver);
  ImGui::Begin("Tracking");
  ImGui::Text("tracker: %s", state.trackerName.c_str());
  ImGui::Text("status: %s", state.lastStatus.c_str());
  TrackerParams& p = state.settings.tracker;
  bool changed = false;
  ImGui::PushItemWidth(140);

  int mode = p.mode == TrackingMode::SixDof ? 0 : 1;
  if (ImGui::Combo("Mode", &mode, "full 6-DOF\0homography\0")) {
    p.mode = mode == 0 ? TrackingMode::SixDof : TrackingMode::Homography;
    changed = true;
  }
  if (ImGui::CollapsingHeader("Pose estimator", ImGuiTreeNodeFlags_DefaultOpen)) {
    int estimator = p.pose.estimator == PoseEstimatorKind::Standard ? 0 : 1;
    if (ImGui::Combo("Estimator", &estimator, "standard least squares\0regularised\0")) {
      p.pose.estimator =
          estimator == 0 ? PoseEstimatorKind::Standard : PoseEstimatorKind::Regularised;
      changed = true;
    }
    changed |= inputDouble("alpha", p.pose.alpha, 0.1, "%.3f");
    changed |= ImGui::InputInt("AR order", &p.pose.arOrder);
    changed |= inputDouble("Q trans (m/fr)", p.pose.translationSigma, 1e-4, "%.5f");
    changed |= inputDouble("Q rot (rad/fr)", p.pose.rotationSigma, 1e-4, "%.5f");
    changed |= ImGui::InputText("Q file", &p.pose.motionModelFile);
    // Rolling shutter: the readout as a fraction of the frame interval, given or estimated online.
    changed |= inputDouble("RS readout", p.pose.rollingShutterReadout, 0.05, "%.2f");
    changed |= ImGui::Checkbox("estimate readout", &p.pose.estimateRollingShutter);
    // Learned reliability of the map's points and corners (0: the corner model's weights alone).
    changed |= inputDouble("reliability prior", p.pose.reliabilityPriorObservations, 1.0, "%.1f");
    // Above this predicted overlay error (px) a frame is "uncertain" and drawn dimmed (0: off).
    changed |= inputDouble("max predicted px", p.pose.maxPredictedErrorPx, 0.5, "%.1f");
    if (state.rollingShutterReadout)
      ImGui::Text("readout in use: %.3f", *state.rollingShutterReadout);
  }
  if (ImGui::CollapsingHeader("RANSAC", ImGuiTreeNodeFlags_DefaultOpen)) {
    changed |= ImGui::InputInt("iterations", &p.ransac.maxIterations);
    changed |= inputDouble("early support", p.ransac.earlyAcceptSupport, 0.05, "%.2f");
    changed |= ImGui::InputInt("early min iter", &p.ransac.earlyAcceptMinIterations);
  }
  if (ImGui::CollapsingHeader("Matching", ImGuiTreeNodeFlags_DefaultOpen)) {
    changed |= ImGui::InputInt("corr half window", &p.correlation.halfWindow);
    changed |= inputDouble("corr threshold", p.correlation.minScore, 0.05, "%.2f");
    changed |= inputDouble("search half w", p.correlation.searchHalfWidthPx, 1.0, "%.1f");
    changed |= inputDouble("search half h", p.correlation.searchHalfHeightPx, 1.0, "%.1f");
    changed |= ImGui::InputInt("corners @320x240", &p.corners.countAt320x240);
  }
  if (ImGui::CollapsingHeader("Homography mode")) {
    changed |= inputDouble("guided search", p.homography.guidedSearchHalfSizePx, 1.0, "%.1f");
    changed |= inputDouble("reacquire corners x", p.homography.reacquireCornerFactor, 1.0, "%.1f");
    // Needs the camera's K (camera.yml or the simulator's camera).
    changed |= ImGui::Checkbox("rotation model", &p.homography.rotationModel);
  }
  ImGui::PopItemWidth();
  if (changed) state.trackerParamsChanged = true;

  ImGui::Separator();
  ImGui::InputText("YAML", &state.paramsPath);
  if (ImGui::Button("Save")) {
    try {
      state.settings.save(state.paramsPath);
      state.paramsMessage = "saved " + state.paramsPath;
    } catch (const Error& e) {
      state.paramsMessage = e.what();
    }
  }
  ImGui::SameLine();
  if (ImGui::Button("Load")) {
    try {
      state.settings = ViewerSettings::load(state.paramsPath);
      state.trackerParamsChanged = true;
      state.paramsMessage = "loaded " + state.paramsPath;
    } catch (const Error& e) {
      state.paramsMessage = e.what();
    }
  }
  if (!state.paramsMessage.empty()) ImGui::TextWrapped("%s", state.paramsMessage.c_str());
  ImGui::End();
}

}  // namespace reftrack::app
