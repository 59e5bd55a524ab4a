#pragma once
// The simulator's desk scene, built once per test program: its reference eyes A and B and the
// point the cameras look at (contentCentre) are what the placement and sampling tests draw about.
#include "app/simulator/DeskScene.hpp"

namespace reftrack::test {

inline const app::DeskScene& deskScene() {
  static const app::DeskScene scene = app::buildDeskScene();
  return scene;
}

}  // namespace reftrack::test
