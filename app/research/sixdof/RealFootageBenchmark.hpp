#pragma once
// The 6-DOF tracker on real footage with ground truth from a planar target (PlanarTargetTruth):
// a clip of a card on a table (by default ViSP's postcard clip, ../shared/data/planar-videos), the
// card's corners given in frame 0 and followed through the clip, a map prepared from a few of
// its frames with the card's poses (MultiReferencePreparer, as `reftrack prepare --poses` does),
// then the clip tracked by the MultiReferenceTracker and, on the same frames, by the ORB +
// solvePnPRansac + KalmanFilter baseline (OrbPnpKalmanTracker, on the first two references).
// Errors against the card: a 7x7 grid over the card carried from frame 0 by the followed
// homography (independent of the guessed K), and a cube standing on the card's centre projected
// through the card's PnP pose. Speed: thread CPU time per tracked frame, every pass alternating
// the two trackers so both see the same machine load.
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/config/TrackerParams.hpp"
#include "engine/geometry/TumTrajectory.hpp"
#include "engine/reference/ReferencePreparer.hpp"

namespace reftrack::app {

struct RealFootageOptions {
  std::filesystem::path clip;                // a video file (cv::VideoCapture)
  int frames = 0;                            // frames tracked from the start; 0: all
  std::vector<int> references = {0, 100};    // frame indices of the reference images (>= 2)
  std::array<cv::Point2f, 4> targetCorners;  // in frame 0: TL, TR, BR, BL, to a few pixels
  double targetTopEdgeMetres = 0.105;        // the card's TL-TR edge (the world's scale)
  double focalPx = 840.0;                    // fx = fy; principal point at the image centre
  double cubeSideMetres = 0.1;               // the cube on the card's centre (cube error)
  int passes = 3;                            // tracking passes over the clip (timing only)
  bool baseline = true;

  // ViSP's postcard clip: its corners clicked by eye in frame 0, its ~10.5 cm top edge, and
  // the focal length ViSP's tutorial assumes.
  static RealFootageOptions postcard(std::filesystem::path clip);
  void check() const;  // throws reftrack::Error naming the bad option
};

// One frame of reftrack's first pass, for the per-frame CSV (`bench-real --frames-csv`).
struct RealFootageFrame {
  int frame = 0;
  std::string state, message;                   // PoseTrackingResult's state and message
  int referenceA = -1, referenceB = -1;         // the pair in use (-1: none)
  double gridErrorPx = NAN, cubeErrorPx = NAN;  // NaN: no pose or no truth
  // Distance (mm) of the card's camera centre from each reference's, in the card's poses; NaN
  // where the card was not followed.
  std::vector<double> referenceDistanceMm;
  int corners = 0, matchesA = 0, matchesB = 0, threeView = 0, inliers = 0;
  double supportSdPx = NAN;
  // The truth's own consistency: the largest distance (px) between a card corner refined by
  // cornerSubPix in this frame and where the followed homography carries frame 0's corner (the
  // truth's); NaN if not followed.
  double truthCornerShiftPx = NAN;
  std::array<cv::Point2f, 4> cardCorners{};  // the truth's card corners (NaN if not followed)
};

// One tracker over the clip.
struct RealFootageRun {
  std::string name;
  int frames = 0, tracked = 0;
  std::vector<double> gridErrorPx;   // per tracked frame with a followed homography
  std::vector<double> cubeErrorPx;   // per tracked frame with a card pose
  std::vector<double> trackedCpuMs;  // thread CPU of every tracked frame, all passes
  std::map<std::string, std::vector<double>> stageMs;  // PoseTracker stages (wall), first pass
  std::map<std::string, int> noPose;                   // reason -> frames (first pass)
  TumTrajectory estimate;  // first pass, tracked frames (timestamp: frame index / clip fps)
  std::vector<RealFootageFrame> perFrame;  // first pass, every frame (reftrack only)
  double trackedPercent() const { return frames > 0 ? 100.0 * tracked / frames : 0.0; }
};

struct RealFootageResult {
  cv::Size frameSize;
  int clipFrames = 0;      // frames read (tracked frames plus any up to the last reference)
  int followedFrames = 0;  // frames where the card was followed (truth available)
  double aspectRatio = 0.0, aspectRms = 0.0;  // of the card fit (PlanarTargetTruth)
  std::vector<double> referenceBaselinesMm;   // reference i to reference 0
  int mapPoints = 0;
  double rollingShutterReadout = 0.0;  // reftrack's at the end of the first pass
  RealFootageRun reftrack;
  std::optional<RealFootageRun> baseline;
};

// Throws reftrack::Error when the clip cannot be read, is shorter than needed, or a reference
// frame has no card pose.
RealFootageResult runRealFootageBenchmark(const RealFootageOptions& options,
                                          const TrackerParams& params,
                                          const ReferencePreparerParams& prepareParams);

// The q-quantile (q in [0, 1], linear interpolation) of `values`; NaN when empty.
double percentileOf(std::vector<double> values, double q);

// Writes run.perFrame as CSV (one row per frame, header first), atomically.
void writeRealFootageFramesCsv(const RealFootageRun& run, const std::filesystem::path& file);

}  // namespace reftrack::app
