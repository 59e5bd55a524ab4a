#include "FrameArray.hpp"

#include <cstdint>
#include <string>

namespace py = pybind11;

namespace reftrack::python {

namespace {

std::string shapeOf(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// OpenCV addresses a row-major image with any row step: channels, then pixels, contiguous.
bool opencvLayout(const py::array& a, int channels) {
  if (a.ndim() == 3 && a.strides(2) != 1) return false;
  return a.strides(1) == channels && a.strides(0) >= a.shape(1) * channels;
}

}  // namespace

FrameView viewFrame(const py::handle& frame) {
  if (!py::isinstance<py::array>(frame))
    throw py::type_error("frame must be a numpy array (uint8, HxW grey or HxWx3 BGR), got " +
                         std::string(py::str(py::type::of(frame).attr("__name__"))));
  FrameView view;
  view.pixels = py::reinterpret_borrow<py::array>(frame);
  const py::array& a = view.pixels;
  if (!a.dtype().is(py::dtype::of<std::uint8_t>()))
    throw py::type_error("frame must be a uint8 image, got dtype " +
                         std::string(py::str(a.dtype())));
  const bool grey = a.ndim() == 2 || (a.ndim() == 3 && a.shape(2) == 1);
  if (!grey && !(a.ndim() == 3 && a.shape(2) == 3))
    throw py::value_error("frame must be HxW (grey) or HxWx3 (BGR), got shape " + shapeOf(a));
  const int channels = grey ? 1 : 3;
  if (!opencvLayout(a, channels)) {
    view.pixels = py::array_t<std::uint8_t, py::array::c_style>::ensure(a);
    if (!view.pixels) throw py::error_already_set();
    view.copied = true;
  }
  const py::array& p = view.pixels;
  view.mat = cv::Mat(static_cast<int>(p.shape(0)), static_cast<int>(p.shape(1)), CV_8UC(channels),
                     const_cast<void*>(p.data()), static_cast<std::size_t>(p.strides(0)));
  return view;
}

}  // namespace reftrack::python
