// poses: the camera pose of every frame of a clip, tracked against a map from `reftrack prepare`.
//   poses MAP_FOLDER CLIP      CLIP: a video file, or a quoted glob of images ('frames/*.png')
#include <cstdio>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

#include "engine/api/Tracker.hpp"
#include "engine/core/Error.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s MAP_FOLDER VIDEO_OR_IMAGE_GLOB\n", argv[0]);
    return 2;
  }
  try {
    reftrack::Tracker tracker = reftrack::Tracker::openMap(argv[1]);
    const std::string clip = argv[2];
    std::vector<cv::String> images;
    cv::VideoCapture video;
    if (clip.find('*') != std::string::npos)
      cv::glob(clip, images);  // sorted by name
    else if (!video.open(clip))
      throw reftrack::Error("cannot open the video '" + clip + "'");
    int tracked = 0, frames = 0;
    for (std::size_t i = 0;; ++i) {
      cv::Mat frame;
      if (video.isOpened())
        video >> frame;
      else if (i < images.size())
        frame = cv::imread(images[i], cv::IMREAD_COLOR);
      if (frame.empty()) break;
      const reftrack::Tracker::Result r = tracker.track(frame);
      ++frames;
      if (!r.worldToCamera) {  // initialising or lost: no pose, and why
        std::printf("%d %s: %s\n", r.frameIndex, toString(r.state), r.reason.c_str());
        continue;
      }
      ++tracked;
      // World -> camera (X_camera = R X_world + t) as (t, r), r axis-angle; SD from covariance.
      const reftrack::Vector6d x = r.worldToCamera->toVector6();
      const Eigen::Matrix<double, 6, 1> sd = r.covariance->diagonal().cwiseSqrt();
      const Eigen::Vector3d c = r.worldToCamera->cameraCentre();
      std::printf(
          "%d tracking t %.4f %.4f %.4f r %.5f %.5f %.5f | SD t %.2f mm r %.3f deg |"
          " camera at %.3f %.3f %.3f m, references %d+%d\n",
          r.frameIndex, x[0], x[1], x[2], x[3], x[4], x[5], 1000 * sd.head<3>().maxCoeff(),
          sd.tail<3>().maxCoeff() * 180 / std::numbers::pi, c.x(), c.y(), c.z(), r.referenceA,
          r.referenceB);
    }
    std::printf("%d of %d frames tracked\n", tracked, frames);
    return 0;
  } catch (const reftrack::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
