#pragma once
// PlaneMultiWorld: PlaneWorld's textured plane seen by N reference cameras — an exact synthetic
// MultiReferenceMap for the multi-reference tracker tests (see below).
#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "PlaneWorld.hpp"
#include "engine/geometry/LookAt.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack::test {

// A -> camera pose of a camera at `eye` (camera A's frame) looking at `target`, image x along
// A's x as far as possible.
inline RigidPose lookAtInA(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  return lookAtPose(eye, target, Eigen::Vector3d(0, -1, 0));  // A's image up is -y
}

// References i = 0..N-1 at (x_i, 0, 0) in camera A's frame, all looking at the plane point in
// front of A (0, 0, 1). Every view is an exact homography of the plane; the map points are the
// corners found within 1 px of each other's exact transfer (union over all pairs), with their
// exact 3D points on the plane.
struct PlaneMultiWorld : PlaneWorld {
  std::vector<RigidPose> referencesFromA;  // A -> reference i

  explicit PlaneMultiWorld(const std::vector<double>& xs) {
    for (double x : xs) referencesFromA.push_back(cameraAt(x));
  }
  static RigidPose cameraAt(double x, double y = 0.0, double z = 0.0) {
    return lookAtInA(Eigen::Vector3d(x, y, z), Eigen::Vector3d(0.0, 0.0, 1.0));
  }
  // Frame k of a path along the references' line: the camera at x, bobbing a little up and down
  // and in depth, looking at the plane.
  static RigidPose cameraAlong(double x, int k) {
    return cameraAt(x, 0.02 * std::sin(0.3 * k), 0.03 * std::sin(0.17 * k));
  }
  RigidPose worldToCamera(const RigidPose& fromA) const { return fromA * T_A; }

  // The plane point seen at pixel p by the camera A -> C, in A's frame.
  Eigen::Vector3d backProject(const RigidPose& T_AC, cv::Point2f p) const {
    const Eigen::Vector3d nC = T_AC.rotation() * n;
    const double dC = d + nC.dot(T_AC.translation());
    const Eigen::Vector3d ray = K.inverse() * Eigen::Vector3d(p.x, p.y, 1.0);
    return T_AC.inverse() * (ray * (dC / nC.dot(ray)));
  }

  MultiReferenceMap map() const {
    MultiReferenceMap m;
    m.camera = PinholeCamera(K, size);
    m.poseSource = "synthetic plane, " + std::to_string(referencesFromA.size()) + " references";
    CornerParams cp;
    cp.countAt320x240 = 200;
    cp.detectAtPaperScale = false;
    const CornerDetector detector(cp);
    const int n = static_cast<int>(referencesFromA.size());
    std::vector<int> offset{0};
    for (int i = 0; i < n; ++i) {
      ReferenceView v;
      v.name = "reference_" + std::to_string(i) + ".png";
      v.T = worldToCamera(referencesFromA[static_cast<std::size_t>(i)]);
      v.image = render(referencesFromA[static_cast<std::size_t>(i)], 1 + i);
      for (const Corner& c : detector.detect(v.image))
        v.corners.push_back({c.position, c.contrast});
      offset.push_back(offset.back() + static_cast<int>(v.corners.size()));
      m.views.push_back(std::move(v));
    }
    // Union-find over (view, corner) nodes.
    std::vector<int> parent(static_cast<std::size_t>(offset.back()));
    std::iota(parent.begin(), parent.end(), 0);
    const std::function<int(int)> root = [&](int x) {
      while (parent[static_cast<std::size_t>(x)] != x)
        x = parent[static_cast<std::size_t>(x)] =
            parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      return x;
    };
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) {
        const RigidPose& Ti = referencesFromA[static_cast<std::size_t>(i)];
        const RigidPose& Tj = referencesFromA[static_cast<std::size_t>(j)];
        const cv::Matx33d H = homography(Tj) * homography(Ti).inv();  // i pixels -> j pixels
        const auto& ci = m.views[static_cast<std::size_t>(i)].corners;
        const auto& cj = m.views[static_cast<std::size_t>(j)].corners;
        for (int a = 0; a < static_cast<int>(ci.size()); ++a) {
          const cv::Point2d pb = applyH(H, ci[static_cast<std::size_t>(a)].pixel);
          for (int b = 0; b < static_cast<int>(cj.size()); ++b)
            if (cv::norm(cv::Point2d(cj[static_cast<std::size_t>(b)].pixel) - pb) < 1.0) {
              parent[static_cast<std::size_t>(root(offset[static_cast<std::size_t>(i)] + a))] =
                  root(offset[static_cast<std::size_t>(j)] + b);
              break;
            }
        }
      }
    std::vector<std::vector<PointObservation>> tracks(parent.size());
    for (int i = 0; i < n; ++i)
      for (int c = 0;
           c < offset[static_cast<std::size_t>(i) + 1] - offset[static_cast<std::size_t>(i)]; ++c)
        tracks[static_cast<std::size_t>(root(offset[static_cast<std::size_t>(i)] + c))].push_back(
            {i, c});
    for (const std::vector<PointObservation>& t : tracks) {
      if (t.size() < 2) continue;
      bool repeated = false;  // two corners of one view: ambiguous, dropped
      for (std::size_t k = 1; k < t.size(); ++k) repeated |= t[k].view == t[k - 1].view;
      if (repeated) continue;
      const PointObservation& o = t.front();
      const Eigen::Vector3d inA = backProject(referencesFromA[static_cast<std::size_t>(o.view)],
                                              m.views[static_cast<std::size_t>(o.view)]
                                                  .corners[static_cast<std::size_t>(o.corner)]
                                                  .pixel);
      m.points.push_back({T_A.inverse() * inA, t});
    }
    return m;
  }
};

// Pose errors against the exact ground truth: camera translation in millimetres, rotation in
// degrees.
inline double translationErrorMm(const RigidPose& estimate, const RigidPose& truth) {
  return RigidPose::translationDistance(estimate, truth) * 1000.0;
}
inline double rotationErrorDeg(const RigidPose& estimate, const RigidPose& truth) {
  return RigidPose::rotationDistance(estimate, truth) * 180.0 / CV_PI;
}

}  // namespace reftrack::test
