#pragma once
// Synthetic chessboard photographs for the calibration tests: a high-resolution board texture
// warped by the exact plane homography K [r1 r2 t] (exact for a plane), rendered at 3x the
// resolution with K scaled about pixel centres and area-averaged down, plus mild sensor noise.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "engine/calibration/CalibrationBoard.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack::test {

// The camera the calibration tests render with, and must recover.
inline const cv::Size kBoardViewSize(640, 480);
inline Eigen::Matrix3d boardViewK() {
  Eigen::Matrix3d K;
  K << 620.0, 0, 322.5, 0, 610.0, 236.8, 0, 0, 1;
  return K;
}

// fx, fy, cx and cy of `camera` each within `fraction` of K's.
inline void expectIntrinsicsNear(const PinholeCamera& camera, const Eigen::Matrix3d& K,
                                 double fraction) {
  EXPECT_NEAR(camera.fx(), K(0, 0), fraction * K(0, 0));
  EXPECT_NEAR(camera.fy(), K(1, 1), fraction * K(1, 1));
  EXPECT_NEAR(camera.cx(), K(0, 2), fraction * K(0, 2));
  EXPECT_NEAR(camera.cy(), K(1, 2), fraction * K(1, 2));
}

// Texture of a chessboard board with a one-square white margin; `pixelsPerSquare` per square.
inline cv::Mat chessboardTexture(const CalibrationBoard& board, int pixelsPerSquare) {
  const int squaresX = board.columns + 1, squaresY = board.rows + 1;
  cv::Mat tex((squaresY + 2) * pixelsPerSquare, (squaresX + 2) * pixelsPerSquare, CV_8UC1,
              cv::Scalar(255));
  for (int y = 0; y < squaresY; ++y)
    for (int x = 0; x < squaresX; ++x)
      if ((x + y) % 2 == 0)
        tex(cv::Rect((x + 1) * pixelsPerSquare, (y + 1) * pixelsPerSquare, pixelsPerSquare,
                     pixelsPerSquare))
            .setTo(0);
  return tex;
}

// Board-to-camera pose looking at the board centre from `distance` metres, the board tilted by
// `tiltXDeg`/`tiltYDeg` about its centre, rolled by `rollDeg`, its centre shifted by (dx, dy) m.
inline RigidPose boardPose(const CalibrationBoard& board, double tiltXDeg, double tiltYDeg,
                           double rollDeg, double dx, double dy, double distance) {
  const double d2r = std::numbers::pi / 180.0;
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(rollDeg * d2r, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(tiltXDeg * d2r, Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(tiltYDeg * d2r, Eigen::Vector3d::UnitY()))
                                .toRotationMatrix();
  const Eigen::Vector3d centre(0.5 * (board.columns - 1) * board.squareMetres,
                               0.5 * (board.rows - 1) * board.squareMetres, 0.0);
  return RigidPose(R, Eigen::Vector3d(dx, dy, distance) - R * centre);
}

// The board seen by camera K (image `size`) at pose `boardToCamera`; grey, 8-bit.
inline cv::Mat renderBoardView(const CalibrationBoard& board, const cv::Mat& texture,
                               int pixelsPerSquare, const Eigen::Matrix3d& K, cv::Size size,
                               const RigidPose& boardToCamera, int noiseSeed) {
  const int ss = 3;
  Eigen::Matrix3d S;
  S << ss, 0, 0.5 * (ss - 1), 0, ss, 0.5 * (ss - 1), 0, 0, 1;
  // Texture pixel (u, v) has its centre at board point ((u + 0.5) s - 2 q, (v + 0.5) s - 2 q):
  // one margin square and one board square lie before the first inner corner.
  const double q = board.squareMetres, s = q / pixelsPerSquare;
  Eigen::Matrix3d A;
  A << s, 0, 0.5 * s - 2 * q, 0, s, 0.5 * s - 2 * q, 0, 0, 1;
  Eigen::Matrix3d Rt;
  Rt.col(0) = boardToCamera.rotation().col(0);
  Rt.col(1) = boardToCamera.rotation().col(1);
  Rt.col(2) = boardToCamera.translation();
  const Eigen::Matrix3d H = S * K * Rt * A;
  cv::Matx33d Hcv;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Hcv(r, c) = H(r, c);
  cv::Mat big, out;
  cv::warpPerspective(texture, big, Hcv, cv::Size(size.width * ss, size.height * ss),
                      cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(140));
  cv::resize(big, out, size, 0, 0, cv::INTER_AREA);
  cv::Mat noise(size, CV_16SC1);
  cv::RNG rng(noiseSeed);
  rng.fill(noise, cv::RNG::NORMAL, 0, 2.0);
  cv::Mat noisy;
  out.convertTo(noisy, CV_16SC1);
  noisy += noise;
  noisy.convertTo(out, CV_8UC1);
  return out;
}

// Fifteen varied, fully visible views of `board` (about 0.5 m away, tilted up to 40 degrees).
inline std::vector<RigidPose> variedBoardPoses(const CalibrationBoard& board) {
  struct P {
    double tx, ty, roll, dx, dy, dist;
  };
  const std::vector<P> poses = {{0, 0, 0, 0, 0, 0.55},
                                {35, 0, 5, 0.02, 0.01, 0.6},
                                {-35, 0, -5, -0.02, 0, 0.6},
                                {0, 35, 10, 0, 0.02, 0.6},
                                {0, -35, -10, 0.01, -0.02, 0.6},
                                {25, 25, 20, -0.05, -0.04, 0.6},
                                {-25, 25, -15, 0.05, -0.04, 0.6},
                                {25, -25, 0, -0.05, 0.04, 0.6},
                                {-25, -25, 30, 0.05, 0.04, 0.6},
                                {15, 0, 90, 0, 0, 0.65},
                                {40, 10, -5, 0, 0, 0.7},
                                {-10, 40, 5, 0, 0, 0.7},
                                {10, -15, 0, -0.07, -0.05, 0.7},
                                {-10, 15, 0, 0.07, 0.05, 0.7},
                                {20, -20, 45, 0.0, 0.0, 0.5}};
  std::vector<RigidPose> out;
  for (const P& p : poses) out.push_back(boardPose(board, p.tx, p.ty, p.roll, p.dx, p.dy, p.dist));
  return out;
}

}  // namespace reftrack::test
