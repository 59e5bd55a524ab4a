#include "app/viewer/StatsPanel.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace reftrack::app {

namespace {

void plotSeries(const char* label, const std::vector<float>& values) {
  float lo = 0, hi = 0;
  bool any = false;
  for (float v : values)
    if (std::isfinite(v)) {
      lo = any ? std::min(lo, v) : v;
      hi = any ? std::max(hi, v) : v;
      any = true;
    }
  const float pad = std::max(1e-3f, 0.1f * (hi - lo));
  char overlay[48];
  if (any && std::isfinite(values.back()))
    std::snprintf(overlay, sizeof overlay, "%+.3f", values.back());
  else
    std::snprintf(overlay, sizeof overlay, "-");
  ImGui::PlotLines(label, values.data(), static_cast<int>(values.size()), 0, overlay, lo - pad,
                   hi + pad, ImVec2(0, 36));
}

float finiteMax(const std::vector<float>& values) {
  float hi = 0;
  for (float v : values)
    if (std::isfinite(v)) hi = std::max(hi, v);
  return hi;
}

void plotErrorSeries(const char* label, const std::vector<float>& values, float top) {
  char overlay[48];
  if (!values.empty() && std::isfinite(values.back()))
    std::snprintf(overlay, sizeof overlay, "%.2f px", values.back());
  else
    std::snprintf(overlay, sizeof overlay, "-");
  ImGui::PlotLines(label, values.data(), static_cast<int>(values.size()), 0, overlay, 0.0f, top,
                   ImVec2(0, 36));
}

}  // namespace

void drawStatsPanel(const StatsHistory& stats, const cv::Rect2f& placement) {
  ImGui::SetNextWindowPos({placement.x, placement.y}, ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize({placement.width, placement.height}, ImGuiCond_FirstUseEver);
  ImGui::Begin("Stats");
  ImGui::Text("%.1f fps over %zu frames", stats.meanFps(), stats.frames().size());
  if (!stats.frames().empty()) {
    const FrameStats& last = stats.frames().back();
    ImGui::Text("frame %d: %s, %d matches, %d inliers", last.index, last.status.c_str(),
                last.matches, last.inliers);
    if (!last.advice.empty()) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.3f, 1.0f));
      ImGui::TextWrapped("%s", last.advice.c_str());
      ImGui::PopStyleColor();
    }
    for (const StageTime& s : last.stages)
      ImGui::Text("  %-14s %7.2f ms", s.name.c_str(), s.milliseconds);
  }
  ImGui::PushItemWidth(-40);
  static const char* kNames[6] = {"tx", "ty", "tz", "rx", "ry", "rz"};
  for (int c = 0; c < 6; ++c) plotSeries(kNames[c], stats.poseSeries(c));
  plotSeries("inl", stats.inlierSeries());
  // Overlay error of the drawn object: predicted from the pose covariance and, with ground truth,
  // the true one beside it on the same scale (0 to the larger of the two's maxima).
  const std::vector<float> predicted = stats.predictedErrorSeries();
  const std::vector<float> measured = stats.trueErrorSeries();
  const float top = 1.1f * std::max({0.5f, finiteMax(predicted),
                                     stats.groundTruthLoaded() ? finiteMax(measured) : 0.0f});
  plotErrorSeries("pred", predicted, top);
  if (stats.groundTruthLoaded()) plotErrorSeries("true", measured, top);
  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace reftrack::app
