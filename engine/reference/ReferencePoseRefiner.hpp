#pragma once
// ReferencePoseRefiner (issue 14 item 3): the reference poses a fiducial (marker, grid, --poses)
// gives are good to a fraction of a pixel at the fiducial, but for references a few centimetres
// apart a few hundredths of a degree of relative rotation shift every disparity by a fraction of
// a pixel, i.e. every triangulated depth by centimetres, so the pose error grows away from the
// references (simulator, 4 cm baseline: reference B turned 0.1 deg about the marker doubles the
// cube error; see tests/engine/reference/ReferencePoseRefiner_test.cpp). The hundreds of corner
// matches between the references fix their relative rotation and the direction of their
// translation far better than the fiducial; the fiducial still fixes the world frame (reference
// 0 is held) and the scale. A Ceres adjustment (Cauchy loss on the reprojection residuals):
// every other reference's pose is free under a prior in the terms a fiducial at the world origin
// fixes well (where the origin projects: SD originSdPx; the camera's distance from it: SD
// translationSdMetres) and one on its orientation (rotationSdDeg); the points are free. A
// reference that does not see the origin in front of it gets a prior on its centre instead.
// The residuals are measured at each observation's peak (PointObservation::peak: the pixel the
// point was triangulated from), or at its corner where the map has no peak (format 1/2 maps).
#include <vector>

#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack {

struct ReferencePoseRefinerParams {
  double originSdPx = 0.2;             // the world origin's projection (prior SD, pixels)
  double translationSdMetres = 0.002;  // distance to the origin (or the centre) (prior SD)
  // The given orientations' error (prior SD). A fiducial's poses are good to about this; the
  // matches of a textured 3D scene fix the relative rotation far better and override it, those of
  // a plane seen over a short baseline barely (real postcard clip: at 1 deg the planar map's
  // ambiguity turned B 0.30 deg and the error away from the references grew 1.79 -> 2.17 px; at
  // 0.1 deg B turned 0.056 deg and it fell to 1.57 px).
  double rotationSdDeg = 0.1;
  double cornerSdPx = 0.3;  // reprojection residual SD (Cauchy scale, pixels)
  int maxIterations = 50;
  void check() const;  // throws reftrack::Error naming the bad field
};

struct ReferencePoseRefinement {
  int observations = 0;
  double initialRmsPx = 0.0, finalRmsPx = 0.0;     // reprojection RMS over every observation
  std::vector<double> movedMillimetres, movedDeg;  // per reference (0 for reference 0)
  bool converged = false;
};

// Refines map.views[1..].T and map.points[*].world in place; reference 0 is not touched. A map
// without points or with one reference is left as it is.
ReferencePoseRefinement refineReferencePoses(MultiReferenceMap& map,
                                             const ReferencePoseRefinerParams& params = {});

}  // namespace reftrack
