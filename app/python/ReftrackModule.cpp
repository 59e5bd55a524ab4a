// The Python module `reftrack`: reftrack::Tracker (engine/api/Tracker.hpp) for notebooks and
// scripts. Type stubs: reftrack.pyi (keep the two in step).
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "FrameArray.hpp"
#include "TrackerParamsArgument.hpp"
#include "engine/api/Tracker.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/core/Error.hpp"

namespace py = pybind11;
using reftrack::Tracker;
using Result = reftrack::Tracker::Result;

namespace {

std::optional<Eigen::Matrix3d> homographyOf(const Result& r) {
  if (!r.homography) return std::nullopt;
  Eigen::Matrix3d H;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H(i, j) = (*r.homography)(i, j);
  return H;
}

std::string describe(const Result& r) {
  std::string s = "<reftrack.Result frame " + std::to_string(r.frameIndex) + " " +
                  reftrack::toString(r.state) + ", " + std::to_string(r.inliers) + " inliers";
  if (!r.reason.empty()) s += ", " + r.reason;
  return s + ">";
}

}  // namespace

PYBIND11_MODULE(reftrack, m) {
  m.doc() =
      "reftrack: marker-less AR tracking against calibrated reference images. "
      "Tracker.open_map(folder) (6-DOF, a map from `reftrack prepare`) or "
      "Tracker.open_reference(image, camera=...) (homography mode); then track(frame) per frame.";
  m.attr("__version__") = REFTRACK_VERSION;
  py::register_exception<reftrack::Error>(m, "Error", PyExc_RuntimeError);

  py::class_<Result>(m, "Result", "What Tracker.track found in one frame.")
      .def_property_readonly(
          "state", [](const Result& r) { return reftrack::toString(r.state); },
          "'initialising' (no pose since open or reset), 'tracking', 'lost' or 'uncertain' "
          "(tracked, but predicted_error_px exceeds pose.max_predicted_error_px: the pose is "
          "given, not to be drawn as if exact)")
      .def_readonly("reason", &Result::reason,
                    "why not tracking; while tracking, how the pose was found, if notable")
      .def_readonly("frame_index", &Result::frameIndex, "0 for the first frame after open/reset")
      .def_property_readonly(
          "world_to_camera",
          [](const Result& r) -> std::optional<Eigen::Matrix4d> {
            if (!r.worldToCamera) return std::nullopt;
            return r.worldToCamera->matrix4();
          },
          "4x4 float64 world -> camera (X_camera = R X_world + t, world = the marker's frame), "
          "None unless tracking")
      .def_property_readonly(
          "covariance",
          [](const Result& r) -> std::optional<Eigen::Matrix<double, 6, 6>> {
            return r.covariance;
          },
          "6x6 covariance of (t, r) of world_to_camera (metres, radians; r axis-angle), or None")
      .def_readonly("predicted_error_px", &Result::predictedErrorPx,
                    "6-DOF, with a pose: the overlay error in pixels the covariance predicts for "
                    "the overlay points (Tracker.set_overlay_points), else None")
      .def_property_readonly("homography", &homographyOf,
                             "3x3 reference pixel -> frame pixel (homography mode), or None")
      .def_readonly("inliers", &Result::inliers, "matches supporting the result")
      .def_readonly("reference_a", &Result::referenceA, "6-DOF: the references in use (-1: none)")
      .def_readonly("reference_b", &Result::referenceB)
      .def_readonly("relocalised", &Result::relocalised, "6-DOF: the relocaliser found this pose")
      .def_readonly("milliseconds", &Result::milliseconds, "time spent in the engine's track()")
      .def("__repr__", &describe);

  py::class_<Tracker>(m, "Tracker",
                      "Tracks frames, in order, against a map (6-DOF) or a reference image.")
      .def_static(
          "open_map",
          [](const std::filesystem::path& folder, const py::object& params,
             const std::optional<std::filesystem::path>& motionModel, bool realtime) {
            reftrack::TrackerParams p = reftrack::python::trackerParamsFrom(params);
            if (motionModel) p.pose.motionModelFile = motionModel->string();
            py::gil_scoped_release release;
            Tracker t = Tracker::openMap(folder, p);
            t.setRealTimeBudget(realtime);
            return t;
          },
          py::arg("folder"), py::kw_only(), py::arg("params") = py::none(),
          py::arg("motion_model") = py::none(), py::arg("realtime") = false,
          "6-DOF tracking against a map folder written by `reftrack prepare`. params: None, a "
          "YAML file (`--params`) or a dict of its sections; motion_model: a `fit-motion` file; "
          "realtime: budget the search after a loss in measured CPU time (a live camera) instead "
          "of its modelled work (the default: the same frames give the same poses on any "
          "machine).")
      .def_static(
          "open_reference",
          [](const std::filesystem::path& image, const std::optional<std::filesystem::path>& camera,
             const py::object& params) {
            const reftrack::TrackerParams p = reftrack::python::trackerParamsFrom(params);
            py::gil_scoped_release release;
            return Tracker::openReference(image, camera.value_or(std::filesystem::path()), p);
          },
          py::arg("image"), py::kw_only(), py::arg("camera") = py::none(),
          py::arg("params") = py::none(),
          "Homography tracking against one reference image; camera (camera.yml) adds the "
          "rotation-only model and the rotation pose.")
      .def(
          "track",
          [](Tracker& tracker, const py::handle& frame) {
            const reftrack::python::FrameView view = reftrack::python::viewFrame(frame);
            py::gil_scoped_release release;
            return tracker.track(view.mat);
          },
          py::arg("frame"),
          "Tracks the next frame: a uint8 numpy image of the map's size, HxW grey or HxWx3 BGR "
          "(read in place, not copied, when its rows are contiguous).")
      .def("reset", &Tracker::reset, "Forget the past: the next frame is tracked as a first one.")
      .def(
          "set_overlay_points",
          [](Tracker& tracker, const Eigen::Matrix<double, Eigen::Dynamic, 3>& points) {
            std::vector<Eigen::Vector3d> world;
            for (Eigen::Index i = 0; i < points.rows(); ++i) world.emplace_back(points.row(i));
            tracker.setOverlayPoints(world);
          },
          py::arg("points"),
          "6-DOF: the drawn object's points (Nx3, world frame, metres) whose overlay error "
          "Result.predicted_error_px predicts; an empty (0x3) array restores the default (the "
          "corners of the box holding the central part of the map's points).")
      .def_property_readonly("mode",
                             [](const Tracker& t) {
                               return t.mode() == Tracker::Mode::SixDof ? "6dof" : "homography";
                             })
      .def_property_readonly(
          "image_size",
          [](const Tracker& t) {
            return py::make_tuple(t.imageSize().width, t.imageSize().height);
          },
          "(width, height) of the frames track() accepts")
      .def_property_readonly("camera_matrix", &Tracker::camera, "3x3 K, or None when unknown");
}
