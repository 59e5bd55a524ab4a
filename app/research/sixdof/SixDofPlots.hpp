#pragma once
// PNG plots of 6-DOF experiment runs: the cube-vertex error over time per tracker, and the
// motion components of standard least squares vs the regulariser on the same frames (Fig. 13).
#include <filesystem>
#include <vector>

#include "app/research/sixdof/SixDofRuns.hpp"

namespace reftrack::app {

void writeCubeErrorPlot(const SimulatedSequence& s, const std::vector<const TrackerRun*>& runs,
                        const std::filesystem::path& png);
void writeMotionComponentsPlot(const SimulatedSequence& s, const TrackerRun& standard,
                               const TrackerRun& regularised, const std::filesystem::path& png);

}  // namespace reftrack::app
