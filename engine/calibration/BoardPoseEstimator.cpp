#include "engine/calibration/BoardPoseEstimator.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

// Mean grey level of a 5x5 window (clipped to the image) around `p`.
double meanAround(const cv::Mat& gray, cv::Point2f p) {
  const cv::Rect window =
      cv::Rect(cvRound(p.x) - 2, cvRound(p.y) - 2, 5, 5) & cv::Rect(0, 0, gray.cols, gray.rows);
  return window.area() > 0 ? cv::mean(gray(window))[0] : 128.0;
}

// A chessboard's corners come from either end (a 180-degree turn of the board fits the same
// grid). The printed board tells the ends apart when COLS + ROWS is odd: the square diagonally
// outside the first inner corner is black (CalibrationBoard's frame, as OpenCV's pattern), the
// one outside the last is white. The corners are put in that order (reversed when the dark
// square is at the last corner). Boards with COLS + ROWS even are symmetric and left as found.
void orderFromDarkCorner(const cv::Mat& image, const CalibrationBoard& board,
                         BoardObservation& obs) {
  const cv::Size grid = board.cornerGrid();
  const std::size_t n = obs.imagePoints.size();
  if (board.kind != CalibrationBoard::Kind::Chessboard || (grid.width + grid.height) % 2 == 0 ||
      n != static_cast<std::size_t>(grid.area()) || grid.width < 2 || grid.height < 2)
    return;
  cv::Mat gray;
  if (image.channels() == 3)
    cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  else
    gray = image;
  const std::vector<cv::Point2f>& p = obs.imagePoints;
  const std::size_t cols = static_cast<std::size_t>(grid.width);
  // Half a square outward along the row and the column from a corner of the grid.
  const auto outside = [&](std::size_t corner, std::size_t alongRow, std::size_t alongColumn) {
    return p[corner] + 0.5f * (p[corner] - p[alongRow]) + 0.5f * (p[corner] - p[alongColumn]);
  };
  const double first = meanAround(gray, outside(0, 1, cols));
  const double last = meanAround(gray, outside(n - 1, n - 2, n - 1 - cols));
  if (first > last) std::reverse(obs.imagePoints.begin(), obs.imagePoints.end());
}

}  // namespace

BoardPoseEstimator::BoardPoseEstimator(CalibrationBoard board, PinholeCamera camera,
                                       double maxReprojectionRmsPx)
    : detector_((board.check(), std::move(board))),
      camera_(std::move(camera)),
      maxRmsPx_(maxReprojectionRmsPx) {
  camera_.check();
  if (!(maxRmsPx_ > 0.0)) throw Error("the board pose's reprojection limit must be positive");
}

std::optional<BoardPose> BoardPoseEstimator::estimate(const cv::Mat& image,
                                                      const std::string& imageName,
                                                      std::string* why) const {
  if (image.size() != camera_.imageSize())
    throw Error("image '" + imageName + "' is " + std::to_string(image.cols) + "x" +
                std::to_string(image.rows) + " but the camera is for " +
                std::to_string(camera_.imageSize().width) + "x" +
                std::to_string(camera_.imageSize().height) + " images");
  const std::optional<BoardObservation> seen = detector_.detect(image);
  if (!seen || seen->imagePoints.size() < 4) {
    if (why)
      *why = "board " + board().toString() + " not found in " + imageName +
             " (is the whole board in view, and are its inner corners COLSxROWS as given?)";
    return std::nullopt;
  }
  BoardObservation obs = *seen;
  orderFromDarkCorner(image, board(), obs);
  const std::vector<cv::Point2f> ideal = camera_.undistortPixels(obs.imagePoints);
  const cv::Matx33d K = camera_.Kcv();
  cv::Mat rvec, tvec;
  // IPPE for the planar start, then LM on all corners.
  if (!cv::solvePnP(obs.objectPoints, ideal, K, cv::noArray(), rvec, tvec, false,
                    cv::SOLVEPNP_IPPE))
    throw Error("the board pose could not be solved in " + imageName);
  cv::solvePnPRefineLM(obs.objectPoints, ideal, K, cv::noArray(), rvec, tvec);
  cv::Matx33d Rcv;
  cv::Rodrigues(rvec, Rcv);
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = Rcv(r, c);
  BoardPose out;
  out.worldToCamera =
      RigidPose(R, Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)));
  out.corners = static_cast<int>(ideal.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < ideal.size(); ++i) {
    const cv::Point3f& X = obs.objectPoints[i];
    const Eigen::Vector2d p = camera_.project(out.worldToCamera, Eigen::Vector3d(X.x, X.y, X.z));
    sum += (p - Eigen::Vector2d(ideal[i].x, ideal[i].y)).squaredNorm();
  }
  out.reprojectionRmsPx = std::sqrt(sum / static_cast<double>(ideal.size()));
  if (out.worldToCamera.translation().z() <= 0.0)
    throw Error("the board in " + imageName + " solves to a pose behind the camera");
  if (out.reprojectionRmsPx > maxRmsPx_) {
    std::ostringstream ss;
    ss << "the board corners in " << imageName << " reproject with " << out.reprojectionRmsPx
       << " px RMS (limit " << maxRmsPx_ << "): wrong camera calibration or board?";
    throw Error(ss.str());
  }
  return out;
}

}  // namespace reftrack
