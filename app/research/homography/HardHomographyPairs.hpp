#pragma once
// The hard pair sets of issue 26: five pairs each, built like the Oxford viewpoint and
// zoom + rotation sets the project does not hold (graf, wall, boat, bark) from the images and the
// simulator it has, each frame with its exact homography, another exposure and light, defocus,
// vignetting, sensor noise and JPEG compression:
// - graf-sim: ubc/img1 (800x640) seen from 20-60 degrees, the camera swinging sideways about the
//   wall, beyond the reference's borders texture it does not hold (the image mirrored);
// - wall-sim: the simulator's brick wall (BrickWallScene), reference 1000x700 from one camera,
//   frames 880x680 from another (as Oxford's wall), viewpoints 20-60 degrees;
// - boat-sim: bikes/img1 cut to 850x680, zoom 1.3-2.9x with in-plane rotation;
// - bark-sim: trees/img1 cut to 765x512, zoom 1.4-4x with in-plane rotation;
// - tiles-sim: a wall of square tiles (BrickWallScene), reference 800x600, frames 640x480 from
//   another camera, tilted 15-40 degrees, zoomed 1-2.5x and rotated (a chessboard-like grid).
// A set whose image is missing under the data folder is left out (the simulated ones need none).
#include <cstdint>
#include <filesystem>
#include <vector>

#include "app/research/homography/HomographyPair.hpp"

namespace reftrack::app {

// The names of the hard sets, in the order buildHardHomographyPairs gives them.
const std::vector<std::string>& hardPairSetNames();

// dataDir: the Oxford-style folder holding ubc/, bikes/ and trees/ (img1.png each);
// wallSupersample: rays per pixel (squared) of the simulated walls (4: the experiments; fewer
// renders faster, with some aliasing: 2 x 2 changed 3 of the 10 simulated pairs' outcomes).
std::vector<HomographyPair> buildHardHomographyPairs(const std::filesystem::path& dataDir,
                                                     double noiseSigma, std::uint64_t seed,
                                                     int wallSupersample = 4);

// Writes pairs as Oxford-style folders: dir/<set>/img1.png (the reference), img2..6.png and
// H1to{N}p.xml, so `track --reference` and `--data` read them like the real sets. At most five
// frames per set; throws reftrack::Error when a file cannot be written.
void saveHomographyPairs(const std::vector<HomographyPair>& pairs,
                         const std::filesystem::path& dir);

}  // namespace reftrack::app
