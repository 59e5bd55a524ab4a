#pragma once
// ReferencePairExperiment (`reftrack experiment-reference-pair`): what limits the map of two
// references taken from a recording with ground truth. It measures
//  - how well the given poses agree with the images: the epipolar distance of SIFT ratio-test
//    matches (mutual, ratio 0.75) under the given relative pose, beside the same distances under
//    the relative pose the images give (essential matrix, RANSAC 1 px, on those matches);
//  - the map `prepare` builds from the pair (MultiReferencePreparer with the given parameters):
//    its statistics and its preparation time (thread CPU);
//  - the map's accuracy in other frames with true poses: each map point is projected into the
//    frame and the reference window of its first observation, warped by the point's
//    fronto-parallel plane, is searched within +-searchRadiusPx of the projection (warped NCC);
//    the offset of the peak is the point's error there (as far as the ground truth allows: the
//    same measure on points triangulated from the SIFT matches gives the truth's own level);
//  - the tracker's measurements there: the tracker (default parameters) run in order up to the last
//    check frame, and at each check frame its inliers' frame corners against their map points'
//    projections under the true pose and under its own (a measurement off the truth, or a pose).
#include <string>
#include <vector>

#include "app/research/sixdof/GroundTruthSequence.hpp"
#include "engine/reference/ReferencePreparer.hpp"

namespace reftrack::app {

struct ReferencePairExperimentOptions {
  GroundTruthSequenceSpec sequence;
  int refA = 0, refB = 40;
  std::vector<int> checkFrames;  // frames the map is checked in (true poses)
  ReferencePreparerParams prepare;
  int searchRadiusPx = 8;  // search window around each projection in a check frame
  double minScore = 0.8;   // a point counts as found in a check frame at this NCC or better
};

// Prints the report to stdout. Throws reftrack::Error on a bad sequence, frame or pose.
void runReferencePairExperiment(const ReferencePairExperimentOptions& options);

}  // namespace reftrack::app
