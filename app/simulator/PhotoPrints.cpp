#include "app/simulator/PhotoPrints.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <opencv2/imgcodecs.hpp>

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

// DeskScene's Lambertian shading (light from the front-left), so a print is as bright as paper
// lying where it lies.
double shading(const Eigen::Vector3d& n) {
  const Eigen::Vector3d light = Eigen::Vector3d(-0.3, -0.5, 0.8).normalized();
  return 0.55 + 0.45 * std::max(0.0, n.normalized().dot(light));
}

render::TexturedMesh print(const Eigen::Vector3d& origin, const Eigen::Vector3d& right,
                           const Eigen::Vector3d& down, const cv::Mat& photo) {
  render::TexturedMesh m;
  m.positions = {origin.cast<float>(), (origin + right).cast<float>(),
                 (origin + right + down).cast<float>(), (origin + down).cast<float>()};
  m.uvs = {{0.f, 0.f}, {1.f, 0.f}, {1.f, 1.f}, {0.f, 1.f}};
  m.indices = {0, 1, 2, 0, 2, 3};
  photo.convertTo(m.texture, CV_8UC3, shading(down.cross(right)));
  return m;
}

}  // namespace

std::string defaultPhotoFile() {
  return std::string(REFTRACK_ASSETS_DIR) + "/textures/cookie-box.jpg";
}

std::vector<render::TexturedMesh> photoPrintMeshes(const std::string& photoFile) {
  const std::string file = photoFile.empty() ? defaultPhotoFile() : photoFile;
  const cv::Mat photo = cv::imread(file, cv::IMREAD_COLOR);
  if (photo.empty()) throw Error("simulator: cannot read the photograph '" + file + "'");
  const Eigen::Vector3d ex = Eigen::Vector3d::UnitX(), ey = Eigen::Vector3d::UnitY(),
                        ez = Eigen::Vector3d::UnitZ();
  // On the desk (z = 0), texture x along world x, texture down along world -y.
  const double deskW = 0.24, deskH = 0.16;
  // The back wall (y = 1), texture x along world x, texture down along world -z.
  const double wallW = 0.6, wallH = 0.4;
  return {print({0.17, 0.14, 0.001}, deskW * ex, -deskH * ey, photo),
          print({-0.2, 0.998, 0.65}, wallW * ex, -wallH * ez, photo)};
}

}  // namespace reftrack::app
