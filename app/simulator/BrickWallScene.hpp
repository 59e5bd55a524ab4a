#pragma once
// BrickWallScene: a wall of a repeated pattern — bricks in running bond or square tiles separated
// by mortar joints — for registration under repetitive texture (issue 26). Every unit has its own
// shade, speckle, chips and slightly uneven edges, so the pattern repeats while no two units are
// identical, as on a real brick wall. The joints are recessed (jointDepthM): a view from the side
// sees into them, their floor and the units' shaded sides shifting against the faces with the
// viewpoint, as on a real wall. The reflectance is a function of the wall point (metres, hashed
// from the seed), so views at any distance or angle see detail at their own scale, and a view is
// rendered by casting each pixel's sub-samples into the scene (exact area sampling, no texture
// resolution limit). The units' faces lie in the plane z = 0 (x right, y down); a pinhole camera's
// view of that plane is the homography K [r1 r2 t] (planeToImage), so the exact reference ->
// frame homography of the faces in two views, of any sizes and intrinsics, is known.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>

namespace reftrack::app {

struct BrickWallStyle {
  enum class Pattern { RunningBond, Tiles };
  Pattern pattern = Pattern::RunningBond;
  double unitWidthM = 0.215, unitHeightM = 0.065;  // a brick (tiles: e.g. 0.1 x 0.1)
  double jointM = 0.010;                           // mortar joint width
  cv::Scalar unitColour{55, 75, 150};              // BGR mean unit colour (grey levels)
  double unitShadeSpread = 0.16;                   // relative SD of a unit's brightness
  cv::Scalar jointColour{185, 190, 195};           // BGR mortar colour
  double speckle = 0.10;                           // relative amplitude of the fine texture
  double chipsPerUnit = 0.4;                       // mean dark / light spots per unit
  double chipRadius = 0.25;                        // their largest radius / the unit's height
  double chipContrast = 0.25;                      // relative shade change of a spot
  double edgeJitterM = 0.002;                      // each unit edge moves by up to this
  double jointDepthM = 0.008;                      // the joints' floor lies this far behind
  void check() const;                              // throws reftrack::Error naming the field
};

class BrickWallTexture {
 public:
  explicit BrickWallTexture(std::uint64_t seed, BrickWallStyle style = {});  // throws on style

  // BGR reflectance (grey levels 0..255) of the face plane at wall point (x, y) metres (a unit's
  // face, or the joint seen head-on); the wall is unbounded.
  cv::Vec3f at(double x, double y) const;
  // What a ray sees that crosses the face plane at (x0, y0) and would reach the joints' floor
  // (z = jointDepthM) at (x1, y1): a unit's face, a unit's shaded side, or the joint's floor.
  cv::Vec3f seen(double x0, double y0, double x1, double y1) const;

  const BrickWallStyle& style() const { return style_; }

 private:
  struct Cell {  // the unit a wall point belongs to
    bool inUnit = false;
    std::array<std::uint64_t, 3> bits{};  // the unit's random bits (hashed from its position)
    double lx = 0, ly = 0;                // position relative to the unit's nominal top-left corner
    // The unit's k-th uniform value in [0, 1) (k < 24: 8 bits each).
    double random(int k) const {
      return static_cast<double>((bits[static_cast<std::size_t>(k / 8)] >> (8 * (k % 8))) & 0xFF) /
             256.0;
    }
  };
  Cell locate(double x, double y) const;
  cv::Vec3f unitColour(double x, double y, const Cell& c) const;
  cv::Vec3f jointColour(double x, double y) const;

  // Value noise (one octave) of cell `cellM` metres at (x, y): smooth, in [-1, 1].
  double noise(double x, double y, double cellM, std::uint64_t salt) const;

  std::uint64_t seed_;
  BrickWallStyle style_;
};

// The homography taking wall points (x, y metres, z = 0) to image pixels: K [r1 r2 t].
cv::Matx33d planeToImage(const Eigen::Matrix3d& K, const Eigen::Matrix4d& worldToCamera);

// A camera pose (world -> camera) looking at wall point `target` from `distanceM`, its optical
// axis tilted by tiltDeg from the wall's normal towards in-wall direction azimuthDeg (0: +x,
// 90: +y), rolled by rollDeg about the optical axis.
Eigen::Matrix4d wallViewPose(const Eigen::Vector2d& target, double distanceM, double tiltDeg,
                             double azimuthDeg, double rollDeg);

// The wall seen by camera K at pose worldToCamera: each pixel the mean of supersample x
// supersample rays (pixel centres at integers, OpenCV's convention), lit by `illumination`
// (a gain per wall point: 1 + gradient . (x, y) metres, clamped at >= 0.2), times `exposure`.
// Rays that miss the wall (behind the camera) see black. CV_32FC3, grey levels.
cv::Mat renderWallView(const BrickWallTexture& wall, const Eigen::Matrix3d& K,
                       const Eigen::Matrix4d& worldToCamera, cv::Size size, int supersample = 4,
                       const Eigen::Vector2d& illuminationGradient = Eigen::Vector2d::Zero(),
                       double exposure = 1.0);

}  // namespace reftrack::app
