#pragma once
// PhotoPrints: real photographs in the simulator's desk scene (CameraEffects::photos) — a print
// lying on the desk right of the marker (0.24 x 0.16 m, 1 mm above the desk) and a poster on the
// back wall (0.6 x 0.4 m, 2 mm in front of it), shaded like the surfaces they lie on. They cover
// neither the marker nor a box, so the world frame and every pose stay as they were.
#include <string>
#include <vector>

#include "render/SceneRenderer.hpp"

namespace reftrack::app {

// The bundled photograph (assets/textures/cookie-box.jpg in the source tree).
std::string defaultPhotoFile();

// Meshes of the prints of `photoFile` ("" = defaultPhotoFile()); throws reftrack::Error when it
// cannot be read.
std::vector<render::TexturedMesh> photoPrintMeshes(const std::string& photoFile);

}  // namespace reftrack::app
