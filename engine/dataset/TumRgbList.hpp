#pragma once
// readTumRgbList: the colour frames of a TUM RGB-D sequence folder, from DIR/rgb.txt — one
// `timestamp filename` per line (seconds; the file name relative to DIR, e.g.
// rgb/1305031102.175304.png),
// '#' lines are comments — in file order. Throws reftrack::Error naming rgb.txt and the line when
// the file is missing or malformed, lists no frame, names an image that does not exist, or when
// timestamps do not increase.
#include <filesystem>
#include <vector>

#include "engine/dataset/StampedImageFile.hpp"

namespace reftrack {

std::vector<StampedImageFile> readTumRgbList(const std::filesystem::path& dir);

}  // namespace reftrack
