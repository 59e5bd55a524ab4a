#include "app/mapview/MapPicture.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <sstream>
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
void drawFrustum(cv::Mat& img, const VirtualCamera& view, const PinholeCamera& camera,
                 const RigidPose& T, double depth, const cv::Scalar& colour,
                 const std::string& label) {
  const Eigen::Matrix3d Kinv = camera.K().inverse();
  const RigidPose cameraToWorld = T.inverse();
  const cv::Size s = camera.imageSize();
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

// Frustum colour of reference i: green, orange, then around the hue circle.
cv::Scalar referenceColour(int i) {
  static const cv::Scalar palette[] = {{80, 220, 80},   {80, 160, 255}, {255, 140, 80},
                                       {220, 90, 220},  {80, 230, 230}, {240, 240, 90},
                                       {140, 110, 255}, {200, 200, 200}};
  return palette[static_cast<std::size_t>(i) % (sizeof palette / sizeof palette[0])];
}

void label(cv::Mat& img, const std::string& text, cv::Point at) {
  cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 0), 4, cv::LINE_AA);
  cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
}

}  // namespace

cv::Mat drawMapPicture(const MultiReferenceMap& map) {
  map.check();
  const cv::Size s = map.camera.imageSize();
  const int n = map.size();
  // Tiles: a grid 2 image widths wide (two per row at full size, more per row scaled down).
  const int columns = std::max(2, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)))));
  const int rows = (n + columns - 1) / columns;
  const double scale = 2.0 / columns;
  const cv::Size tile(static_cast<int>(std::lround(s.width * scale)),
                      static_cast<int>(std::lround(s.height * scale)));
  const int topHeight = rows * tile.height;
  cv::Mat picture(topHeight + s.height, 2 * s.width, CV_8UC3, cv::Scalar(32, 32, 32));
  std::vector<cv::Point2f> origin;
  for (int v = 0; v < n; ++v) {
    const cv::Point at((v % columns) * tile.width, (v / columns) * tile.height);
    origin.emplace_back(static_cast<float>(at.x), static_cast<float>(at.y));
    cv::Mat bgr = toBgr(map.views[static_cast<std::size_t>(v)].image);
    if (scale != 1.0) cv::resize(bgr, bgr, tile, 0, 0, cv::INTER_AREA);
    bgr.copyTo(picture(cv::Rect(at, tile)));
  }
  // Pixel of corner c of view v in the picture.
  const auto inTile = [&](int v, int c) {
    const cv::Point2f p =
        map.views[static_cast<std::size_t>(v)].corners[static_cast<std::size_t>(c)].pixel;
    return origin[static_cast<std::size_t>(v)] +
           cv::Point2f(static_cast<float>((p.x + 0.5) * scale - 0.5),
                       static_cast<float>((p.y + 0.5) * scale - 0.5));
  };

  // Colour: depth of each point in its first reference (5th..95th percentile, blue near, red far).
  std::vector<double> depths;
  for (const MapPoint& p : map.points)
    depths.push_back(
        (map.views[static_cast<std::size_t>(p.observations.front().view)].T * p.world).z());
  double zLo = 0.0, zHi = 0.0;
  if (!depths.empty()) {
    std::vector<double> sorted = depths;
    std::sort(sorted.begin(), sorted.end());
    zLo = sorted[sorted.size() / 20];
    zHi = sorted[sorted.size() - 1 - sorted.size() / 20];
  }
  const int dot = std::max(1, static_cast<int>(std::lround(2 * scale)));
  for (int v = 0; v < n; ++v)
    for (std::size_t c = 0; c < map.views[static_cast<std::size_t>(v)].corners.size(); ++c)
      cv::circle(picture, inTile(v, static_cast<int>(c)), dot, cv::Scalar(170, 170, 170),
                 cv::FILLED, cv::LINE_AA);
  for (std::size_t i = 0; i < map.points.size(); ++i) {
    const cv::Scalar colour = depthColour(depths[i], zLo, zHi);
    const auto& obs = map.points[i].observations;
    // Two references side by side (one row): the match as a line, as in the two-view picture.
    if (obs.size() == 2 && rows == 1 && n == 2)
      cv::line(picture, inTile(obs[0].view, obs[0].corner), inTile(obs[1].view, obs[1].corner),
               colour, std::max(1, s.width / 640), cv::LINE_AA);
    for (const PointObservation& o : obs)
      cv::circle(picture, inTile(o.view, o.corner), dot + 1, colour, cv::FILLED, cv::LINE_AA);
  }
  for (int v = 0; v < n; ++v) {
    const auto& view = map.views[static_cast<std::size_t>(v)];
    int observed = 0;
    for (const MapPoint& p : map.points)
      for (const PointObservation& o : p.observations) observed += o.view == v ? 1 : 0;
    label(picture,
          std::to_string(v) + ": " + std::to_string(view.corners.size()) + " corners, " +
              std::to_string(observed) + " in points",
          cv::Point(static_cast<int>(origin[static_cast<std::size_t>(v)].x) + 10,
                    static_cast<int>(origin[static_cast<std::size_t>(v)].y) + 22));
  }

  // 3D view, in world coordinates, from behind and above the reference cameras.
  cv::Mat bottom = picture(cv::Rect(0, topHeight, 2 * s.width, s.height));
  Eigen::Vector3d cameras = Eigen::Vector3d::Zero();
  for (const ReferenceView& v : map.views) cameras += v.T.cameraCentre();
  cameras /= static_cast<double>(n);
  const RigidPose firstToWorld = map.views.front().T.inverse();
  Eigen::Vector3d target = cameras + firstToWorld.rotation().col(2);  // 1 m ahead by default
  if (!map.points.empty()) {
    target.setZero();
    for (const MapPoint& p : map.points) target += p.world;
    target /= static_cast<double>(map.points.size());
  }
  const double range = std::max((target - cameras).norm(), 1e-3);
  const Eigen::Vector3d back = (cameras - target).normalized();
  const Eigen::Vector3d up = -firstToWorld.rotation().col(1);  // the first reference's image up
  Eigen::Vector3d side = map.views.back().T.cameraCentre() - map.views.front().T.cameraCentre();
  side = side.norm() > 1e-9 ? side.normalized() : Eigen::Vector3d(firstToWorld.rotation().col(0));
  const Eigen::Vector3d eye = cameras + range * (0.9 * back + 0.7 * up - 0.6 * side);
  const VirtualCamera view =
      lookAt(eye, 0.5 * (target + cameras), up, 0.9 * bottom.cols * 0.5, bottom.size());
  for (std::size_t i = 0; i < map.points.size(); ++i)
    if (const auto p = view.project(map.points[i].world))
      cv::circle(bottom, *p, 3, depthColour(depths[i], zLo, zHi), cv::FILLED, cv::LINE_AA);
  for (int v = 0; v < n; ++v)
    drawFrustum(bottom, view, map.camera, map.views[static_cast<std::size_t>(v)].T, 0.25 * range,
                referenceColour(v), std::to_string(v));
  for (int v = 0; v + 1 < n; ++v)
    drawLine(bottom, view, map.views[static_cast<std::size_t>(v)].T.cameraCentre(),
             map.views[static_cast<std::size_t>(v) + 1].T.cameraCentre(),
             cv::Scalar(200, 200, 200));
  std::vector<int> histogram(static_cast<std::size_t>(n) + 1, 0);
  for (const MapPoint& p : map.points) ++histogram[p.observations.size()];
  std::ostringstream seen;
  for (int k = 2; k <= n; ++k)
    if (histogram[static_cast<std::size_t>(k)] > 0)
      seen << " " << histogram[static_cast<std::size_t>(k)] << "x" << k;
  char stats[200];
  std::snprintf(stats, sizeof(stats),
                "%zu 3D points (depth in their first reference %.2f..%.2f m, blue..red), %d "
                "references",
                map.points.size(), zLo, zHi, n);
  label(bottom, stats, {10, 22});
  label(bottom, "seen by (points x references):" + seen.str() + "   " + map.poseSource, {10, 46});
  return picture;
}

cv::Mat drawMapPicture(const ReferenceMap& map) {
  map.check();
  return drawMapPicture(MultiReferenceMap::fromPair(map));
}

}  // namespace reftrack::app
