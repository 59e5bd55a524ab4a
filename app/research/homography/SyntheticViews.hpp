#pragma once
// Views of a planar image with exact homographies, for the registration experiments: the
// homography of a camera tilted, rolled and moved towards the plane (syntheticViewHomography),
// the image resampled through a homography without aliasing (synthesiseView), and the
// photometric change of another exposure under other light (relight).
#include <cstdint>
#include <opencv2/core.hpp>

namespace reftrack::app {

// The homography of a plane seen head-on filling `size` (focal length = width) when the camera
// is tilted by tiltDeg about the in-plane axis at azimuthDeg, rolled by rollDeg about its optical
// axis and moved to 1/scale of the distance, looking at the image centre.
cv::Matx33d syntheticViewHomography(cv::Size size, double tiltDeg, double azimuthDeg, double scale,
                                    double rollDeg);

// `image` seen through H (reference -> frame) in a frame of `frameSize` (empty: the image's
// size): warped at twice the resolution and area-averaged down (no aliasing when zooming out),
// plus Gaussian noise of SD noiseSigma. Outside the image the frame sees `border`
// (cv::BORDER_CONSTANT: black; cv::BORDER_REFLECT_101: the image mirrored, i.e. texture that the
// reference does not hold, as a real view sees beyond the reference's borders).
cv::Mat synthesiseView(const cv::Mat& image, const cv::Matx33d& H, double noiseSigma,
                       std::uint64_t seed, cv::Size frameSize = {},
                       int border = cv::BORDER_CONSTANT);

// Another exposure under other light: out = gain * in * (1 + gradient . (p - centre) / half
// diagonal) + offset, saturated to 8 bits (p the pixel, the gradient's length the relative
// brightness change from the centre to the farthest corner).
cv::Mat relight(const cv::Mat& image, double gain, double offset, cv::Vec2d gradient);

}  // namespace reftrack::app
