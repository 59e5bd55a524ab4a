#include "app/mapview/MapPicture.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>

namespace reftrack::app {

namespace {

cv::Mat toBgr(const cv::Mat& image) {
  cv::Mat out;
  if (image.channels() == 1)
    cv::cvtColor(image, out, cv::COLOR_GRAY2BGR);
  else if (image.channels() == 4)
    cv::cvtColor(image, out, cv::COLOR_BGRA2BGR);
  else
    out = image.clone();
  if (out.depth() != CV_8U) out.convertTo(out, CV_8U, 1.0 / 256.0);
  return out;
}

// Turbo colour of depth z within [lo, hi] (near = blue, far = red).
cv::Scalar depthColour(double z, double lo, double hi) {
  const double t = hi > lo ? std::clamp((z - lo) / (hi - lo), 0.0, 1.0) : 0.5;
  cv::Mat one(1, 1, CV_8UC1, cv::Scalar(static_cast<int>(std::lround(t * 255.0))));
  cv::Mat colour;
  cv::applyColorMap(one, colour, cv::COLORMAP_TURBO);
  const cv::Vec3b c = colour.at<cv::Vec3b>(0, 0);
  return {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])};
}

// A pinhole looking from `eye` at `target` (world), image up along `up`.
struct VirtualCamera {
  Eigen::Matrix3d R;  // world -> camera rotation
  Eigen::Vector3d eye;
  double f;
  cv::Size size;
  std::optional<cv::Point2f> project(const Eigen::Vector3d& X) const {
    const Eigen::Vector3d c = R * (X - eye);
    if (c.z() <= 1e-6) return std::nullopt;
    return cv::Point2f(static_cast<float>(f * c.x() / c.z() + 0.5 * (size.width - 1)),
                       static_cast<float>(f * c.y() / c.z() + 0.5 * (size.height - 1)));
  }
};

VirtualCamera lookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                     const Eigen::Vector3d& up, double f, cv::Size size) {
  const Eigen::Vector3d z = (target - eye).normalized();
  Eigen::Vector3d x = z.cross(-up);
  if (x.norm() < 1e-9) x = z.unitOrthogonal();
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  VirtualCamera cam;
  cam.R.row(0) = x;
  cam.R.row(1) = y;
  cam.R.row(2) = z;
  cam.eye = eye;
  cam.f = f;
  cam.size = size;
  return cam;
}

void drawLine(cv::Mat& img, const VirtualCamera& cam, const Eigen::Vector3d& a,
              const Eigen::Vector3d& b, const cv::Scalar& colour) {
  const auto pa = cam.project(a), pb = cam.project(b);
  if (pa && pb) cv::line(img, *pa, *pb, colour, 2, cv::LINE_AA);
}

// Frustum of a reference camera (world->camera pose T) drawn `depth` metres deep.
void drawFrustum(cv::Mat& img, const VirtualCamera& view, const ReferenceMap& map,
                 const RigidPose& T, double depth, const cv::Scalar& colour,
                 const std::string& label) {
  const Eigen::Matrix3d Kinv = map.camera.K().inverse();
  const RigidPose cameraToWorld = T.inverse();
  const cv::Size s = map.camera.imageSize();
  const Eigen::Vector3d centre = T.cameraCentre();
  Eigen::Vector3d corners[4];
  const double u[4] = {-0.5, s.width - 0.5, s.width - 0.5, -0.5};
  const double v[4] = {-0.5, -0.5, s.height - 0.5, s.height - 0.5};
  for (int i = 0; i < 4; ++i)
    corners[i] = cameraToWorld * (depth * (Kinv * Eigen::Vector3d(u[i], v[i], 1.0)));
  for (int i = 0; i < 4; ++i) {
    drawLine(img, view, centre, corners[i], colour);
    drawLine(img, view, corners[i], corners[(i + 1) % 4], colour);
  }
  // The image's top edge is marked by a small triangle ("up").
  const Eigen::Vector3d topMid = 0.5 * (corners[0] + corners[1]);
  const Eigen::Vector3d tip = topMid + 0.3 * (topMid - 0.5 * (corners[2] + corners[3]));
  drawLine(img, view, corners[0], tip, colour);
  drawLine(img, view, corners[1], tip, colour);
  if (const auto p = view.project(centre))
    cv::putText(img, label, *p + cv::Point2f(6, -6), cv::FONT_HERSHEY_SIMPLEX, 0.8, colour, 2,
                cv::LINE_AA);
}

}  // namespace

cv::Mat drawMapPicture(const ReferenceMap& map) {
  map.check();
  const cv::Size s = map.camera.imageSize();
  cv::Mat picture(2 * s.height, 2 * s.width, CV_8UC3, cv::Scalar(32, 32, 32));
  cv::Mat top = picture(cv::Rect(0, 0, 2 * s.width, s.height));
  toBgr(map.imageA).copyTo(top(cv::Rect(0, 0, s.width, s.height)));
  toBgr(map.imageB).copyTo(top(cv::Rect(s.width, 0, s.width, s.height)));

  double zLo = 1e300, zHi = -1e300;
  std::vector<double> depths;
  for (const ReferenceMatch& m : map.matches) depths.push_back(m.pointA.z());
  if (!depths.empty()) {
    std::vector<double> sorted = depths;
    std::sort(sorted.begin(), sorted.end());
    zLo = sorted[sorted.size() / 20];  // 5th..95th percentile: outliers do not flatten the scale
    zHi = sorted[sorted.size() - 1 - sorted.size() / 20];
  }

  const float lineWidth = std::max(1.0f, static_cast<float>(s.width) / 640.0f);
  const cv::Point2f offsetB(static_cast<float>(s.width), 0.0f);
  for (const ReferenceCorner& c : map.cornersA)
    cv::circle(top, c.pixel, 2, cv::Scalar(170, 170, 170), cv::FILLED, cv::LINE_AA);
  for (const ReferenceCorner& c : map.cornersB)
    cv::circle(top, c.pixel + offsetB, 2, cv::Scalar(170, 170, 170), cv::FILLED, cv::LINE_AA);
  for (size_t i = 0; i < map.matches.size(); ++i) {
    const ReferenceMatch& m = map.matches[i];
    const cv::Scalar colour = depthColour(depths[i], zLo, zHi);
    const cv::Point2f a = map.cornersA[static_cast<size_t>(m.cornerA)].pixel;
    const cv::Point2f b = map.cornersB[static_cast<size_t>(m.cornerB)].pixel + offsetB;
    cv::line(top, a, b, colour, static_cast<int>(lineWidth), cv::LINE_AA);
    cv::circle(top, a, 3, colour, cv::FILLED, cv::LINE_AA);
    cv::circle(top, b, 3, colour, cv::FILLED, cv::LINE_AA);
  }
  const auto label = [&](cv::Mat& img, const std::string& text, cv::Point at) {
    cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 0), 4, cv::LINE_AA);
    cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255, 255, 255), 1,
                cv::LINE_AA);
  };
  label(top, "A: " + std::to_string(map.cornersA.size()) + " corners", {10, 22});
  label(top, "B: " + std::to_string(map.cornersB.size()) + " corners", {s.width + 10, 22});

  // 3D view, in world coordinates: points P_w = T_A^-1 P_A.
  cv::Mat bottom = picture(cv::Rect(0, s.height, 2 * s.width, s.height));
  const RigidPose aToWorld = map.T_A.inverse();
  std::vector<Eigen::Vector3d> world;
  for (const ReferenceMatch& m : map.matches) world.push_back(aToWorld * m.pointA);
  const Eigen::Vector3d cA = map.T_A.cameraCentre(), cB = map.T_B.cameraCentre();
  const Eigen::Vector3d cameras = 0.5 * (cA + cB);
  Eigen::Vector3d target = cameras + aToWorld.rotation().col(2);  // 1 m ahead of A by default
  if (!world.empty()) {
    target.setZero();
    for (const Eigen::Vector3d& p : world) target += p;
    target /= static_cast<double>(world.size());
  }
  const double range = std::max((target - cameras).norm(), 1e-3);
  const Eigen::Vector3d back = (cameras - target).normalized();
  const Eigen::Vector3d up = -aToWorld.rotation().col(1);  // camera A's image up
  const Eigen::Vector3d side = (cB - cA).normalized();
  const Eigen::Vector3d eye = cameras + range * (0.9 * back + 0.7 * up - 0.6 * side);
  const VirtualCamera view =
      lookAt(eye, 0.5 * (target + cameras), up, 0.9 * bottom.cols * 0.5, bottom.size());
  for (size_t i = 0; i < world.size(); ++i)
    if (const auto p = view.project(world[i]))
      cv::circle(bottom, *p, 3, depthColour(depths[i], zLo, zHi), cv::FILLED, cv::LINE_AA);
  drawFrustum(bottom, view, map, map.T_A, 0.25 * range, cv::Scalar(80, 220, 80), "A");
  drawFrustum(bottom, view, map, map.T_B, 0.25 * range, cv::Scalar(80, 160, 255), "B");
  drawLine(bottom, view, cA, cB, cv::Scalar(200, 200, 200));
  char stats[160];
  std::snprintf(stats, sizeof(stats),
                "%zu 3D points (depth in A %.2f..%.2f m, blue..red), baseline %.0f mm",
                map.matches.size(), depths.empty() ? 0.0 : zLo, depths.empty() ? 0.0 : zHi,
                (cA - cB).norm() * 1000.0);
  label(bottom, stats, {10, 22});
  label(bottom, map.poseSource, {10, 46});
  return picture;
}

}  // namespace reftrack::app
