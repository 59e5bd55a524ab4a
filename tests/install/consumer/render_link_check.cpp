// Links reftrack::render from the installed package (its GL, OSMesa, EGL, GLFW dependencies).
#include <cstdio>

#include "render/CameraProjection.hpp"

int main() {
  Eigen::Matrix3d K;
  K << 100, 0, 31.5, 0, 100, 23.5, 0, 0, 1;
  const Eigen::Matrix4d P = reftrack::render::glProjectionFromK(K, {64, 48}, 0.1, 10.0);
  std::printf("GL projection P(0,0) = %.4f\n", P(0, 0));
  return 0;
}
