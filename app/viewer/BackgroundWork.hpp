#pragma once
// Helpers for the viewer's worker threads (live calibration, live mapping): whether a task's
// result is ready without waiting, and the message of whatever exception it threw.
#include <chrono>
#include <exception>
#include <future>
#include <opencv2/core.hpp>
#include <string>

namespace reftrack::app {

template <typename T>
bool ready(const std::future<T>& f) {
  return f.valid() && f.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

// The error text of any exception a worker may have thrown.
inline std::string errorText(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const cv::Exception& e) {
    return std::string("OpenCV: ") + e.err;
  } catch (const std::exception& e) {
    return e.what();
  }
}

}  // namespace reftrack::app
