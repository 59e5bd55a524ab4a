#pragma once
// CameraProjection: OpenGL matrices for an OpenCV pinhole camera, exact to the pixel.
//
// A camera-frame point X = (X, Y, Z) (OpenCV axes: x right, y down, z forward) must land at
// pixel (u, v) = K X / Z, pixel centres at integer coordinates (pixel (0,0) covers
// [-0.5,0.5]^2) and image row 0 at the top of the viewport. GL eye coordinates are
// (X, -Y, -Z) (openCvToGlCamera), and the viewport maps NDC x in [-1,1] to [0,W] with fragment
// centres at i + 0.5, so u = W (x_ndc + 1)/2 - 0.5 and v = H (1 - y_ndc)/2 - 0.5. With
// K = [fx s cx; 0 fy cy; 0 0 1] that gives, in eye coordinates (x_e, y_e, z_e):
//
//       | 2fx/W  -2s/W   1 - 2(cx+0.5)/W         0        |
//   P = |   0    2fy/H   2(cy+0.5)/H - 1         0        |
//       |   0      0     -(f+n)/(f-n)      -2fn/(f-n)     |
//       |   0      0          -1                 0        |
//
// (n, f: near and far plane distances). Depth buffer values d map back to Z = f n / (f - d(f-n)).
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <utility>
#include <vector>

namespace reftrack::render {

// The projection P above. Throws reftrack::Error naming the bad input (non-finite K, focal
// length <= 0, empty image, near <= 0 or far <= near).
Eigen::Matrix4d glProjectionFromK(const Eigen::Matrix3d& K, cv::Size imageSize, double nearPlane,
                                  double farPlane);

// diag(1, -1, -1, 1): OpenCV camera axes to GL eye axes (y up, looking down -z).
Eigen::Matrix4d openCvToGlCamera();

// P * openCvToGlCamera() * worldToCamera: world points straight to clip coordinates.
Eigen::Matrix4d glViewProjection(const Eigen::Matrix3d& K, cv::Size imageSize,
                                 const Eigen::Matrix4d& worldToCamera, double nearPlane,
                                 double farPlane);

// K for the image scaled by an integer factor s about the pixel-centre convention:
// u' = s u + (s - 1)/2 (each pixel becomes an s x s block whose centre is the old centre).
Eigen::Matrix3d supersampledK(const Eigen::Matrix3d& K, int factor);

// Camera-frame depth Z (metres) of a depth-buffer value d in [0,1); 0 for d >= 1 (cleared).
double depthBufferToMetres(double d, double nearPlane, double farPlane);

// CPU projection for overlays drawn in pixel space: pixel K(RX+t)/Z of a world point, or nullopt
// when the point is not beyond the near plane (Z <= nearPlane).
std::optional<Eigen::Vector2d> projectToPixel(const Eigen::Matrix3d& K,
                                              const Eigen::Matrix4d& worldToCamera,
                                              const Eigen::Vector3d& worldPoint, double nearPlane);

// The segment AB clipped to Z >= nearPlane in the camera frame, projected to pixels; nullopt
// when it lies wholly in front of the near plane.
std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> projectSegmentToPixels(
    const Eigen::Matrix3d& K, const Eigen::Matrix4d& worldToCamera, const Eigen::Vector3d& a,
    const Eigen::Vector3d& b, double nearPlane);

// Lens distortion (OpenCV's coefficients k1,k2,p1,p2[,k3[,k4,k5,k6]]; empty or all zero: none).
// Pixels of camera-frame points (Z > 0) as cv::projectPoints puts them; a point farther from the
// optical axis than lensValidRadius (normalised image radius) comes out NaN: beyond it the radial
// model turns back and would fold the point into the image. Throws reftrack::Error for a
// coefficient count other than 0, 4, 5 or 8.
std::vector<Eigen::Vector2d> projectThroughLens(const Eigen::Matrix3d& K,
                                                const std::vector<double>& distortion,
                                                const std::vector<Eigen::Vector3d>& cameraPoints);
// The normalised radius at which the radial distortion r (1 + k1 r^2 + ...) / (1 + k4 r^2 + ...)
// stops growing (searched up to 10; infinity without distortion or when it never turns back).
double lensValidRadius(const std::vector<double>& distortion);

// projectToPixel through the lens.
std::optional<Eigen::Vector2d> projectToPixel(const Eigen::Matrix3d& K,
                                              const std::vector<double>& distortion,
                                              const Eigen::Matrix4d& worldToCamera,
                                              const Eigen::Vector3d& worldPoint, double nearPlane);

// The segment AB clipped to Z >= nearPlane as a polyline of pixels (empty when it lies wholly in
// front of the near plane). Without distortion: its two end pixels. With distortion the 3-D
// segment is cut into pieces whose ideal images are at most `maxStepPx` long (at most 1024), so
// the straight edge bends as the lens bends it (a 4 px step keeps the chord within 0.01 px of the
// curve for k1 = -0.3); points beyond lensValidRadius are NaN (draw only finite neighbours).
std::vector<Eigen::Vector2d> projectSegmentThroughLens(const Eigen::Matrix3d& K,
                                                       const std::vector<double>& distortion,
                                                       const Eigen::Matrix4d& worldToCamera,
                                                       const Eigen::Vector3d& a,
                                                       const Eigen::Vector3d& b, double nearPlane,
                                                       double maxStepPx = 4.0);

}  // namespace reftrack::render
