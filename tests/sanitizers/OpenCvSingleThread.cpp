// Linked into reftrack_app (so the `reftrack` CLI and app_tests) in the ThreadSanitizer build only
// (tests/sanitizers/Sanitizers.cmake). OpenCV's parallel_for_ runs on TBB, whose synchronisation
// ThreadSanitizer cannot see (libtbb is not instrumented), so every parallel loop, OpenCV's own
// (cv::cvtColor) as well as ours (DeskScene), is reported as a race between a TBB worker and the
// caller that waited for it. One OpenCV thread runs those loops on the calling thread: the threads
// left to check are the project's own (and FFmpeg's and Mesa's, which synchronise through
// pthreads, which ThreadSanitizer intercepts). OPENCV_FOR_THREADS_NUM=1 is not enough: OpenCV 4.6
// reads it only in cv::setNumThreads(-1).
#include <opencv2/core/utility.hpp>

namespace {

const bool openCvSingleThreaded = (cv::setNumThreads(1), true);

}  // namespace
