#pragma once
// DeskScene: the simulator's fixed world, the same for every run. World frame = marker frame:
// origin at the marker centre, x right, y up on the printed marker (away from the cameras), z out
// of the desk. A 2 x 2 m desk (z = 0) carries the ArUco marker on a white sheet and five boxes of
// different sizes; walls stand behind and beside it up to 1.2 m. Every surface has its own
// procedural texture, with Lambertian shading from a fixed light baked in. Reference cameras look
// at the content from the front, ~0.9 m from the marker and ~36 deg off its normal.
#include <Eigen/Core>
#include <vector>

#include "engine/reference/MarkerSpec.hpp"
#include "render/SceneRenderer.hpp"

namespace reftrack::app {

struct DeskScene {
  std::vector<render::TexturedMesh> meshes;
  MarkerSpec marker;                                        // DICT_6X6_250, id 23, side 0.2 m
  Eigen::Vector3d contentCentre = Eigen::Vector3d::Zero();  // where the cameras look
  Eigen::Vector3d referenceEyeA = Eigen::Vector3d::Zero();  // optical centres, world frame
  Eigen::Vector3d referenceEyeB = Eigen::Vector3d::Zero();  // A moved 0.25 m along +x
};

DeskScene buildDeskScene();

}  // namespace reftrack::app
