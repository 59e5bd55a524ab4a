#include "app/research/correlation/CorrelationDecayExperiment.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"
#include "engine/matching/NccCorrelation.hpp"
#include "engine/tracking/WarpedCorrelation.hpp"

namespace reftrack::app {

namespace {

// Homography mapping frame-k pixels to V_A pixels through the world plane z = 0.
cv::Matx33d planeHomographyToA(const Eigen::Matrix3d& K, const RigidPose& T_A,
                               const RigidPose& T_k) {
  // Points on the plane: X = (x, y, 0) -> camera c: R_c [x y 0]^T + t_c, i.e. the 3x3 matrix
  // [r1 r2 t] maps (x, y, 1) to camera coordinates; H_c = K [r1 r2 t].
  auto planeToImage = [&](const RigidPose& T) {
    Eigen::Matrix3d M;
    M.col(0) = T.rotation().col(0);
    M.col(1) = T.rotation().col(1);
    M.col(2) = T.translation();
    return Eigen::Matrix3d(K * M);
  };
  const Eigen::Matrix3d H = planeToImage(T_A) * planeToImage(T_k).inverse();
  cv::Matx33d out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = H(r, c);
  return out;
}

bool inside(const Eigen::Vector2d& p, cv::Size size, int margin) {
  return p.x() >= margin && p.y() >= margin && p.x() < size.width - margin &&
         p.y() < size.height - margin;
}

}  // namespace

CorrelationDecayResult runCorrelationDecay(const SimulatedSequence& s, int halfWindow) {
  const ReferenceMap& map = s.preparation.map;
  const RigidPose AtoWorld = map.T_A.inverse();
  const int margin = 3 * halfWindow + 4;
  CorrelationDecayResult result;
  double bestContrast = -1.0;
  for (const ReferenceMatch& m : map.matches) {
    const Eigen::Vector3d X = AtoWorld * m.pointA;
    if (std::abs(X.z()) > 0.002) continue;  // on the desk plane only: its homography is exact
    const ReferenceCorner& c = map.cornersA[static_cast<std::size_t>(m.cornerA)];
    if (c.rmsContrast <= bestContrast) continue;
    bool visible = true;
    for (const StampedPose& p : s.groundTruth.poses) {
      const Eigen::Vector3d Xc = p.worldToCamera * X;
      if (Xc.z() <= 0 || !inside(s.camera.project(Xc), s.camera.imageSize(), margin)) {
        visible = false;
        break;
      }
    }
    if (!visible) continue;
    bestContrast = c.rmsContrast;
    result.referenceCorner = m.cornerA;
    result.worldPoint = X;
  }
  if (result.referenceCorner < 0)
    throw Error("no map point on the desk plane stays in view over the whole sequence");

  cv::Mat grayA, refF;
  cv::cvtColor(map.imageA, grayA, cv::COLOR_BGR2GRAY);
  grayA.convertTo(refF, CV_32F);
  const cv::Point2f pA = map.cornersA[static_cast<std::size_t>(result.referenceCorner)].pixel;
  const Eigen::Vector3d centreA = AtoWorld.translation();
  for (std::size_t k = 0; k < s.frames.size(); ++k) {
    const RigidPose& Tk = s.groundTruth.poses[k].worldToCamera;
    const Eigen::Vector2d pk = s.camera.project(Tk, result.worldPoint);
    const cv::Point2f pK(static_cast<float>(pk.x()), static_cast<float>(pk.y()));
    result.frames.push_back(static_cast<int>(k));
    result.standardScore.push_back(nccAt(s.frames[k], cv::Point(cvRound(pK.x), cvRound(pK.y)),
                                         grayA, cv::Point(cvRound(pA.x), cvRound(pA.y)),
                                         halfWindow));
    cv::Mat frameF;
    s.frames[k].convertTo(frameF, CV_32F);
    const WarpedCorrelation warped(frameF, refF, halfWindow);
    result.warpedScore.push_back(warped.score(
        warped.framePatch(pK), planeHomographyToA(s.camera.K(), map.T_A, Tk), cv::Point2d(pA)));
    const Eigen::Vector3d centreK = Tk.inverse().translation();
    const Eigen::Vector3d a = (centreA - result.worldPoint).normalized();
    const Eigen::Vector3d b = (centreK - result.worldPoint).normalized();
    result.viewAngleDeg.push_back(std::acos(std::clamp(a.dot(b), -1.0, 1.0)) * 180.0 / CV_PI);
  }
  return result;
}

}  // namespace reftrack::app
