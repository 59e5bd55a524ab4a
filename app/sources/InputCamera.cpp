#include "app/sources/InputCamera.hpp"

#include <cstdio>

#include "engine/dataset/DatasetSpec.hpp"
#include "engine/dataset/EurocCamera.hpp"

namespace reftrack::app {

std::optional<PinholeCamera> cameraFromInput(const std::string& input) {
  const std::optional<DatasetSpec> dataset = parseDatasetSpec(input);
  if (!dataset || dataset->layout != DatasetLayout::Euroc) return std::nullopt;
  const std::filesystem::path folder = EurocCamera::findFolder(dataset->dir);
  EurocCamera euroc;
  EurocCamera::readSensor(folder / "sensor.yaml", euroc);
  const PinholeCamera& c = euroc.camera;
  std::printf("camera: from %s (no --camera given): fu %.3f fv %.3f cu %.3f cv %.3f, %dx%d",
              (folder / "sensor.yaml").string().c_str(), c.fx(), c.fy(), c.cx(), c.cy(),
              c.imageSize().width, c.imageSize().height);
  if (c.distortion().size() == 4)
    std::printf(", radial-tangential k1 %.6g k2 %.6g p1 %.6g p2 %.6g", c.distortion()[0],
                c.distortion()[1], c.distortion()[2], c.distortion()[3]);
  std::printf("\n");
  std::fflush(stdout);
  return c;
}

}  // namespace reftrack::app
