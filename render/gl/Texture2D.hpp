#pragma once
// Texture2D: a GL texture holding a cv::Mat (CV_8UC3 BGR or CV_8UC1 grey, shown as grey RGB).
// Texture row 0 is image row 0, so texture coordinate t = 0 is the image top. Re-uploading an
// image of the same size and type reuses the storage (glTexSubImage2D).
#include <opencv2/core.hpp>

namespace reftrack::render {

class Texture2D {
 public:
  Texture2D();
  ~Texture2D();
  Texture2D(const Texture2D&) = delete;
  Texture2D& operator=(const Texture2D&) = delete;
  Texture2D(Texture2D&& other) noexcept;
  Texture2D& operator=(Texture2D&& other) noexcept;

  // Uploads `image` (throws reftrack::Error for an empty image or another pixel type). With
  // `mipmapped` the texture gets mipmaps, trilinear and (if available) anisotropic filtering.
  void upload(const cv::Mat& image, bool mipmapped);
  // Filtering when not mipmapped: nearest (pixel-exact copies) or bilinear (scaled display).
  void setNearestFiltering(bool nearest);
  void bind(int unit) const;
  cv::Size size() const { return size_; }
  unsigned int id() const { return texture_; }

 private:
  unsigned int texture_ = 0;
  cv::Size size_{0, 0};
  int type_ = -1;
  bool mipmapped_ = false;
};

}  // namespace reftrack::render
