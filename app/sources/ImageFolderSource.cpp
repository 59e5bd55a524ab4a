#include "app/sources/ImageFolderSource.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace fs = std::filesystem;

namespace {

bool hasImageExtension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const std::vector<std::string> known = {".png", ".jpg",  ".jpeg", ".bmp",
                                                 ".tif", ".tiff", ".ppm",  ".pgm"};
  return std::find(known.begin(), known.end(), ext) != known.end();
}

bool isGlob(const std::string& s) { return s.find_first_of("*?[") != std::string::npos; }

}  // namespace

bool naturalLess(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const bool da = std::isdigit(static_cast<unsigned char>(a[i]));
    const bool db = std::isdigit(static_cast<unsigned char>(b[j]));
    if (da && db) {
      std::size_t ie = i, je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
      // Compare digit runs by value: strip leading zeros, then by length, then lexically.
      std::size_t is = i, js = j;
      while (is + 1 < ie && a[is] == '0') ++is;
      while (js + 1 < je && b[js] == '0') ++js;
      const std::string_view ra(a.data() + is, ie - is), rb(b.data() + js, je - js);
      if (ra.size() != rb.size()) return ra.size() < rb.size();
      if (ra != rb) return ra < rb;
      if (ie - i != je - j) return ie - i < je - j;  // fewer leading zeros first
      i = ie;
      j = je;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

ImageFolderSource::ImageFolderSource(const std::string& folderOrGlob, double fps, bool anySizes)
    : spec_(folderOrGlob), fps_(fps), anySizes_(anySizes) {
  if (!(std::isfinite(fps) && fps > 0))
    throw Error("image source '" + spec_ + "': fps must be positive");
  if (isGlob(folderOrGlob)) {
    const fs::path pattern(folderOrGlob);
    const fs::path dir = pattern.has_parent_path() ? pattern.parent_path() : fs::path(".");
    if (isGlob(dir.string()))
      throw Error("image pattern '" + spec_ + "': wildcards are allowed in the file name only");
    if (!fs::is_directory(dir))
      throw Error("image pattern '" + spec_ + "': folder '" + dir.string() + "' does not exist");
    // POSIX fnmatch on the file names (cv::glob knows only * and ?, not [...]).
    const std::string namePattern = pattern.filename().string();
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
      if (e.is_regular_file() &&
          fnmatch(namePattern.c_str(), e.path().filename().c_str(), FNM_PERIOD) == 0)
        files_.push_back(e.path());
  } else {
    if (!fs::exists(folderOrGlob)) throw Error("image folder '" + spec_ + "' does not exist");
    if (!fs::is_directory(folderOrGlob))
      throw Error("image folder '" + spec_ + "' is not a folder");
    for (const fs::directory_entry& e : fs::directory_iterator(folderOrGlob))
      if (e.is_regular_file() && hasImageExtension(e.path())) files_.push_back(e.path());
  }
  if (files_.empty())
    throw Error(isGlob(folderOrGlob) ? "image pattern '" + spec_ + "' matches no file"
                                     : "image folder '" + spec_ + "' holds no image");
  std::sort(files_.begin(), files_.end(), [](const fs::path& a, const fs::path& b) {
    return naturalLess(a.filename().string(), b.filename().string());
  });
}

std::optional<Frame> ImageFolderSource::next() {
  if (nextIndex_ >= static_cast<int>(files_.size())) return std::nullopt;
  const fs::path& file = files_[nextIndex_];
  cv::Mat image;
  try {
    image = cv::imread(file.string(), cv::IMREAD_COLOR);
  } catch (const cv::Exception& e) {
    throw Error("image '" + file.string() + "' cannot be read: " + e.err);
  }
  if (image.empty())
    throw Error("image '" + file.string() + "' cannot be read (missing, corrupt or not an image)");
  if (firstSize_.area() == 0) firstSize_ = image.size();
  if (!anySizes_ && image.size() != firstSize_)
    throw Error("image '" + file.string() + "' is " + std::to_string(image.cols) + "x" +
                std::to_string(image.rows) + " but the first image of '" + spec_ + "' is " +
                std::to_string(firstSize_.width) + "x" + std::to_string(firstSize_.height));
  Frame frame{image, nextIndex_, nextIndex_ / fps_};
  ++nextIndex_;
  return frame;
}

void ImageFolderSource::seek(int index) {
  if (index < 0 || index >= static_cast<int>(files_.size()))
    throw Error(description() + ": frame " + std::to_string(index) + " is out of range");
  nextIndex_ = index;
}

std::string ImageFolderSource::description() const {
  return "images '" + spec_ + "' (" + std::to_string(files_.size()) + " frames)";
}

}  // namespace reftrack::app
