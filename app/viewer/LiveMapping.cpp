#include "app/viewer/LiveMapping.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "app/viewer/BackgroundWork.hpp"
#include "engine/core/Error.hpp"
#include "engine/mapping/MetricScale.hpp"
#include "engine/reference/MultiReferencePreparer.hpp"

namespace reftrack::app {

namespace fs = std::filesystem;

namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

double viewAngleDeg(const RigidPose& a, const RigidPose& b) {
  const Eigen::Vector3d za = a.rotation().row(2).transpose(), zb = b.rotation().row(2).transpose();
  return std::acos(std::clamp(za.dot(zb), -1.0, 1.0)) * kRadToDeg;
}

std::string fixed(double v, int digits) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

}  // namespace

LiveMapping::LiveMapping(WorldFrameFiducial fiducial, PinholeCamera camera,
                         MapExtenderParams params, bool background, MapState& state)
    : fiducial_(std::move(fiducial)),
      camera_(std::move(camera)),
      params_(std::move(params)),
      background_(background) {
  params_.tracker.mode = TrackingMode::SixDof;
  params_.check();
  camera_.check();
  state.fiducial = fiducial_->description();
  state.unprepared = false;
  report(state);
}

LiveMapping::LiveMapping(PinholeCamera camera, MapExtenderParams params,
                         UnpreparedMapParams unprepared, bool background, MapState& state)
    : camera_(std::move(camera)),
      params_(std::move(params)),
      unprepared_(std::move(unprepared)),
      background_(background) {
  params_.tracker.mode = TrackingMode::SixDof;
  params_.check();
  camera_.check();
  motion_.emplace(camera_, unprepared_);  // checks unprepared_
  state.fiducial = "none (unprepared: own matches)";
  state.unprepared = true;
  report(state);
}

LiveMapping::~LiveMapping() {
  if (working_.valid()) working_.wait();
  if (motionWork_.valid()) motionWork_.wait();
}

void LiveMapping::fail(MapState& state, const std::string& message) const {
  state.message = message;
  state.messageIsError = true;
}

bool LiveMapping::capture(const Frame& frame, const std::optional<RigidPose>& tracked,
                          MapState& state) {
  if (frame.image.empty()) {
    fail(state, "no frame to capture yet");
    return false;
  }
  if (!fiducial_ && !map_) return captureUnposed(frame, state);
  const std::string name = "frame " + std::to_string(frame.index);
  std::string why;
  Captured c;
  c.image = frame.image.clone();
  c.frameIndex = frame.index;
  std::optional<MeasuredPose> pose;
  if (fiducial_) pose = fiducial_->estimate(frame.image, name, why);
  if (pose) {
    c.pose = *pose;
  } else if (tracked && map_) {
    c.pose = {*tracked, -1.0};
    c.measured = false;
  } else if (fiducial_) {
    fail(state, std::string("cannot capture ") + name + ": no " + fiducial_->kind() +
                    " in view and not tracking (" + why + ")");
    return false;
  } else {
    fail(state, "cannot capture " + name +
                    ": not tracking (once the map is built, further captures are posed by "
                    "tracking it: start near a captured view)");
    return false;
  }
  // Two captures from (almost) the same place cannot triangulate anything.
  const double minBaseline = params_.preparation.minBaselineMetres;
  for (std::size_t i = 0; i < captures_.size(); ++i) {
    const double d =
        (captures_[i].pose.worldToCamera.cameraCentre() - c.pose.worldToCamera.cameraCentre())
            .norm();
    if (d < minBaseline) {
      fail(state, "cannot capture " + name + ": it is " + fixed(d * 1000.0, 1) +
                      " mm from reference " + std::to_string(i) + " (frame " +
                      std::to_string(captures_[i].frameIndex) + "); at least " +
                      fixed(minBaseline * 1000.0, 1) +
                      " mm are needed to triangulate (preparation.min_baseline_m): move the "
                      "camera sideways");
      return false;
    }
  }
  MapCapture shown;
  shown.frameIndex = frame.index;
  shown.timestamp = frame.timestamp;
  shown.poseFrom = !c.measured ? "tracking" : fiducial_ ? fiducial_->kind() : "matches";
  shown.fiducialRmsPx = c.measured ? c.pose.reprojectionRmsPx : -1.0;
  captures_.push_back(std::move(c));
  shown_.push_back(shown);
  thumbnailsStale_ = true;
  state.message = "captured reference " + std::to_string(captures_.size() - 1) + " (" + name +
                  ", pose from the " + shown.poseFrom + ")";
  state.messageIsError = false;
  report(state);
  return true;
}

bool LiveMapping::captureUnposed(const Frame& frame, MapState& state) {
  const std::string name = "frame " + std::to_string(frame.index);
  if (captures_.size() >= 2) {
    fail(state, "cannot capture " + name +
                    ": the first two captures start the map; Build map first (captures after "
                    "it are posed by tracking and added with Add to map)");
    return false;
  }
  Captured c;
  c.image = frame.image.clone();
  c.frameIndex = frame.index;
  c.posed = false;
  std::shared_ptr<const TwoViewKeyframe> keyframe;
  std::optional<TwoViewMotion> motion;
  try {
    keyframe = std::make_shared<const TwoViewKeyframe>(motion_->describe(frame.image));
    if (!captures_.empty()) motion = motion_->estimate(*firstKeyframe_, *keyframe);
  } catch (const std::exception& e) {
    fail(state, "cannot capture " + name + ": " + e.what());
    return false;
  }
  if (const std::string why = motion_->texturelessRefusal(*keyframe, "captured");
      captures_.empty() && !why.empty()) {
    fail(state, "cannot capture " + name + ": " + why);
    return false;
  }
  if (motion && !motion->usable()) {
    showMotion(*motion, frame.index, state);
    fail(state, "cannot capture " + name + ": " + motion->refusal);
    return false;
  }
  MapCapture shown;
  shown.frameIndex = frame.index;
  shown.timestamp = frame.timestamp;
  shown.poseFrom = "matches";
  captures_.push_back(std::move(c));
  shown_.push_back(shown);
  thumbnailsStale_ = true;
  if (captures_.size() == 1) {
    firstKeyframe_ = keyframe;
    state.motion.clear();
    state.motionFrame = -1;
    state.message = "captured reference 0 (" + name +
                    "): now move the camera sideways, about a tenth of its distance to the scene, "
                    "and capture again";
  } else {
    showMotion(*motion, frame.index, state);
    state.message = "captured reference 1 (" + name + ": " + motion->summary() +
                    "); type the distance the camera moved between the two captures into "
                    "Baseline and Build map";
  }
  state.messageIsError = false;
  report(state);
  return true;
}

void LiveMapping::showMotion(const TwoViewMotion& motion, int frameIndex, MapState& state) const {
  state.motion = motion.usable() ? motion.summary() : motion.summary() + ": " + motion.refusal;
  state.motionUsable = motion.usable();
  state.motionFrame = frameIndex;
}

void LiveMapping::measureMotion(const Frame& frame, MapState& state) {
  if (motionWork_.valid() && ready(motionWork_)) {
    const int measured = motionWorkFrame_;
    try {
      showMotion(motionWork_.get(), measured, state);
    } catch (const std::exception& e) {
      state.motion = std::string("motion not measured: ") + e.what();
      state.motionUsable = false;
    }
  }
  const bool waiting = fiducial_ || map_ || captures_.size() != 1 || !firstKeyframe_;
  if (waiting || !background_ || motionWork_.valid() || frame.image.empty() ||
      frame.index == state.motionFrame)
    return;
  // One measurement at a time on a worker thread; the next starts on the frame in hand when it
  // is done (a few per second), so the video never waits for it.
  motionWorkFrame_ = frame.index;
  motionWork_ = std::async(std::launch::async, [estimator = *motion_, first = firstKeyframe_,
                                                image = frame.image.clone()] {
    return estimator.estimate(*first, estimator.describe(image));
  });
}

LiveMapping::Work LiveMapping::buildUnprepared(std::vector<Captured> captures,
                                               double baselineMetres) const {
  std::vector<reftrack::ReferenceImage> images;
  for (const Captured& c : captures)
    images.push_back({c.image, "frame " + std::to_string(c.frameIndex)});
  const UnpreparedInitializer initializer(camera_, params_, unprepared_);
  const std::shared_ptr<std::atomic<int>> done = done_;
  UnpreparedMap built = initializer.build(images, MetricScale::baseline(baselineMetres),
                                          [done](const std::string&) { ++*done; });
  Work w;
  const UnpreparedMapReport& r = built.report;
  w.message = "map built from the captures' own matches (baseline " + fixed(baselineMetres, 3) +
              " m): " + std::to_string(built.prepared.map.size()) + " references, " +
              std::to_string(built.prepared.map.points.size()) + " points, " +
              (r.onPlane ? "the world on the scene's dominant plane"
                         : "the world at the first capture's camera (no dominant plane)");
  w.map = std::move(built.prepared.map);
  w.posesFromMap = true;
  for (std::size_t i = 0; i < captures.size(); ++i) w.added.push_back(static_cast<int>(i));
  return w;
}

LiveMapping::Work LiveMapping::build(std::vector<Captured> captures) const {
  std::vector<reftrack::ReferenceImage> images;
  std::vector<MeasuredPose> poses;
  for (std::size_t i = 0; i < captures.size(); ++i) {
    images.push_back({captures[i].image, "frame " + std::to_string(captures[i].frameIndex)});
    poses.push_back(captures[i].pose);
  }
  const MultiReferencePreparer preparer(camera_, params_.preparation);
  const std::shared_ptr<std::atomic<int>> done = done_;
  const auto progress = [done](const ReferencePairReport&) { ++*done; };
  std::vector<RigidPose> given;
  for (const MeasuredPose& m : poses) given.push_back(m.worldToCamera);
  MultiPreparation p = fiducial_->refinedLikeAMarker()
                           ? preparer.prepare(images, poses, fiducial_->description(), progress)
                           : preparer.prepare(images, given, fiducial_->description(), progress);
  Work w;
  w.message = "map built: " + std::to_string(p.map.size()) + " references, " +
              std::to_string(p.map.points.size()) + " points";
  w.map = std::move(p.map);
  for (std::size_t i = 0; i < captures.size(); ++i) w.added.push_back(static_cast<int>(i));
  return w;
}

LiveMapping::Work LiveMapping::extend(MultiReferenceMap map,
                                      std::vector<std::pair<int, Captured>> pending) const {
  MapExtender extender(std::move(map), params_);
  Work w;
  for (const auto& [index, c] : pending) {
    const std::string why = extender.add(c.image, c.frameIndex, c.pose.worldToCamera);
    if (why.empty())
      w.added.push_back(index);
    else
      w.notes.emplace_back(index, why);
    ++*done_;
  }
  w.map = extender.map();
  w.message = "added " + std::to_string(w.added.size()) + " of " + std::to_string(pending.size()) +
              " reference(s): the map holds " + std::to_string(w.map.size()) + " references, " +
              std::to_string(w.map.points.size()) + " points";
  return w;
}

void LiveMapping::start(std::function<Work()> work, const std::string& label, MapState& state) {
  state.message.clear();
  state.messageIsError = false;
  state.workLabel = label;
  workStart_ = std::chrono::steady_clock::now();
  if (background_) {
    working_ = std::async(std::launch::async, std::move(work));
  } else {
    std::promise<Work> now;
    try {
      now.set_value(work());
    } catch (...) {
      now.set_exception(std::current_exception());
    }
    working_ = now.get_future();
    collect(state);
  }
}

void LiveMapping::collect(MapState& state) {
  try {
    Work w = working_.get();
    for (int i : w.added) {
      shown_[static_cast<std::size_t>(i)].inMap = true;
      shown_[static_cast<std::size_t>(i)].note.clear();
    }
    for (const auto& [i, why] : w.notes) shown_[static_cast<std::size_t>(i)].note = why;
    if (w.posesFromMap)  // unprepared: the captures are now posed, as the map's references
      for (std::size_t k = 0; k < w.added.size() && k < w.map.views.size(); ++k) {
        Captured& c = captures_[static_cast<std::size_t>(w.added[k])];
        c.pose = {w.map.views[k].T, -1.0};
        c.posed = true;
      }
    map_ = std::move(w.map);
    if (!w.added.empty()) forTracking_ = map_;
    state.message = w.message + (w.added.empty() ? "" : "; tracking on it");
    for (const auto& [i, why] : w.notes)
      state.message += "; frame " + std::to_string(shown_[static_cast<std::size_t>(i)].frameIndex) +
                       " not added: " + why;
    state.messageIsError = !w.notes.empty() && w.added.empty();
  } catch (...) {
    fail(state, state.workLabel + " failed: " + errorText(std::current_exception()));
  }
  report(state);
}

bool LiveMapping::buildNow(MapState& state) {
  if (working_.valid()) {
    working_.wait();
    collect(state);
  }
  const bool background = std::exchange(background_, false);
  state.buildRequested = true;
  update(Frame{}, std::nullopt, state);
  background_ = background;
  return map_.has_value() && !state.messageIsError;
}

void LiveMapping::update(const Frame& frame, const std::optional<RigidPose>& tracked,
                         MapState& state) {
  if (ready(working_)) collect(state);
  if (std::exchange(state.clearRequested, false)) {
    if (working_.valid()) {
      fail(state, "wait for the " + state.workLabel + " to finish");
    } else {
      captures_.clear();
      shown_.clear();
      firstKeyframe_.reset();
      state.motion.clear();
      state.motionFrame = -1;
      thumbnailsStale_ = true;
      state.message = map_ ? "captures cleared (the map is kept)" : "captures cleared";
      state.messageIsError = false;
    }
  }
  if (std::exchange(state.captureRequested, false)) capture(frame, tracked, state);
  if (!fiducial_) measureMotion(frame, state);
  const bool build = std::exchange(state.buildRequested, false);
  const bool add = std::exchange(state.addRequested, false);
  if ((build || add) && working_.valid()) {
    fail(state, "busy: " + state.workLabel);
  } else if (build) {
    std::vector<Captured> measured;
    int left = 0;
    for (const Captured& c : captures_) {
      if (c.measured)
        measured.push_back(c);
      else
        ++left;
    }
    std::string baselineError;
    if (!fiducial_) {
      try {
        MetricScale::baseline(state.baselineMetres).check(camera_.imageSize());
      } catch (const Error& e) {
        baselineError = e.what();
      }
    }
    if (!fiducial_ && measured.size() < 2) {
      fail(state, "Build map needs two captures from two places (have " +
                      std::to_string(measured.size()) + ")");
    } else if (!fiducial_ && !baselineError.empty()) {
      fail(state, "Build map needs the distance the camera moved between the two captures: " +
                      baselineError + " (type it into Baseline, in metres)");
    } else if (measured.size() < 2) {
      fail(state, "Build map needs at least two references captured with the " +
                      std::string(fiducial_->kind()) + " in view (have " +
                      std::to_string(measured.size()) + ")");
    } else {
      // Captures from tracking can only be added to the map they were tracked on.
      if (left > 0) {
        std::vector<Captured> kept;
        std::vector<MapCapture> keptShown;
        for (std::size_t i = 0; i < captures_.size(); ++i)
          if (captures_[i].measured) {
            kept.push_back(captures_[i]);
            keptShown.push_back(shown_[i]);
          }
        captures_ = std::move(kept);
        shown_ = std::move(keptShown);
        thumbnailsStale_ = true;
      }
      for (MapCapture& s : shown_) s.inMap = false;
      done_->store(0);
      if (fiducial_) {
        total_ = static_cast<int>(measured.size() * (measured.size() - 1) / 2);
        unit_ = "pairs matched";
        start([this, measured] { return this->build(measured); }, "building the map", state);
      } else {
        total_ = UnpreparedInitializer(camera_, params_, unprepared_).steps(2);
        unit_ = "steps";
        start(
            [this, measured, baseline = state.baselineMetres] {
              return this->buildUnprepared(measured, baseline);
            },
            "building the map from the captures' own matches", state);
      }
      if (left > 0 && !state.messageIsError)
        state.message += (state.message.empty() ? "" : "; ") + std::to_string(left) +
                         " capture(s) posed by tracking left out";
    }
  } else if (add) {
    std::vector<std::pair<int, Captured>> pending;
    for (std::size_t i = 0; i < captures_.size(); ++i)
      if (!shown_[i].inMap) pending.emplace_back(static_cast<int>(i), captures_[i]);
    if (!map_) {
      fail(state, "Add to map needs a map: capture two references and Build map first");
    } else if (pending.empty()) {
      fail(state, "nothing to add: capture a reference first (every capture is in the map)");
    } else {
      done_->store(0);
      total_ = static_cast<int>(pending.size());
      unit_ = "references added";
      start([this, map = *map_, pending] { return this->extend(map, pending); },
            "adding to the map", state);
    }
  }
  if (std::exchange(state.saveRequested, false)) save(state.savePath, state);
  report(state);
}

bool LiveMapping::save(const fs::path& folder, MapState& state) {
  if (!map_) {
    fail(state, "Save map needs a map: Build map first");
    return false;
  }
  if (folder.empty()) {
    fail(state, "Save map: give a folder name");
    return false;
  }
  const fs::path target = fs::absolute(folder).lexically_normal();
  const fs::path parent = target.parent_path();
  const std::string stem = target.filename().string();
  const fs::path staging = parent / ("." + stem + ".partial");
  const fs::path previous = parent / ("." + stem + ".previous");
  std::error_code ignored;
  try {
    if (fs::exists(target) && !fs::is_directory(target))
      throw Error("'" + target.string() + "' exists and is not a folder");
    fs::remove_all(staging, ignored);
    map_->save(staging);
    // Swap into place; an existing map folder is replaced only once the new one is complete.
    fs::remove_all(previous, ignored);
    if (fs::exists(target)) fs::rename(target, previous);
    fs::rename(staging, target);
    fs::remove_all(previous, ignored);
  } catch (const std::exception& e) {
    fs::remove_all(staging, ignored);
    if (!fs::exists(target) && fs::exists(previous)) fs::rename(previous, target, ignored);
    fail(state, "saving the map to '" + folder.string() +
                    "' failed, nothing written (is the disk full?): " + e.what());
    return false;
  }
  state.message =
      "saved the map (" + std::to_string(map_->size()) + " references) to " + folder.string();
  state.messageIsError = false;
  return true;
}

std::optional<MultiReferenceMap> LiveMapping::takeMapForTracking() {
  return std::exchange(forTracking_, std::nullopt);
}

std::vector<RigidPose> LiveMapping::capturePoses() const {
  std::vector<RigidPose> out;
  for (const Captured& c : captures_) out.push_back(c.pose.worldToCamera);
  return out;
}

void LiveMapping::report(MapState& state) {
  const std::vector<unsigned int> ids = [&] {
    std::vector<unsigned int> v;
    for (const MapCapture& c : state.captures) v.push_back(c.thumbnail);
    return v;
  }();
  state.captures = shown_;
  for (std::size_t i = 0; i < state.captures.size() && !thumbnailsStale_; ++i)
    state.captures[i].thumbnail = i < ids.size() ? ids[i] : 0;
  state.pairs.clear();
  const ReferencePreparerParams& p = params_.preparation;
  for (std::size_t a = 0; a < captures_.size(); ++a)
    for (std::size_t b = a + 1; b < captures_.size(); ++b) {
      if (!captures_[a].posed || !captures_[b].posed) continue;  // unprepared, not built yet
      MapCapturePair pair;
      pair.a = static_cast<int>(a);
      pair.b = static_cast<int>(b);
      const RigidPose &Ta = captures_[a].pose.worldToCamera, &Tb = captures_[b].pose.worldToCamera;
      pair.distanceMetres = (Ta.cameraCentre() - Tb.cameraCentre()).norm();
      pair.angleDeg = viewAngleDeg(Ta, Tb);
      if (pair.distanceMetres < p.minBaselineMetres)
        pair.warning =
            "too close to triangulate (under " + fixed(p.minBaselineMetres * 1000.0, 0) + " mm)";
      else if (pair.angleDeg > p.maxPairViewAngleDeg)
        pair.warning = "too far apart: turned more than " + fixed(p.maxPairViewAngleDeg, 0) +
                       " deg, not matched";
      state.pairs.push_back(pair);
    }
  state.working = working_.valid();
  state.progress =
      state.working ? std::clamp(static_cast<float>(done_->load()) / std::max(1, total_), 0.f, 1.f)
                    : 0.0f;
  state.progressText.clear();
  if (state.working)
    state.progressText =
        std::to_string(done_->load()) + " of " + std::to_string(total_) + " " + unit_ + ", " +
        fixed(std::chrono::duration<double>(std::chrono::steady_clock::now() - workStart_).count(),
              1) +
        " s";
  state.mapReferences = map_ ? map_->size() : 0;
  state.mapPoints = map_ ? map_->points.size() : 0;
}

void LiveMapping::uploadThumbnails(MapState& state) {
  if (!thumbnailsStale_) return;
  thumbnailsStale_ = false;
  thumbnails_.clear();
  for (std::size_t i = 0; i < captures_.size(); ++i) {
    const cv::Mat& image = captures_[i].image;
    const double scale = 96.0 / image.cols;
    cv::Mat small;
    cv::resize(image, small, cv::Size(), scale, scale, cv::INTER_AREA);
    if (small.channels() == 1) cv::cvtColor(small, small, cv::COLOR_GRAY2BGR);
    render::Texture2D texture;
    texture.upload(small, false);
    state.thumbnailSize = small.size();
    if (i < state.captures.size()) state.captures[i].thumbnail = texture.id();
    thumbnails_.push_back(std::move(texture));
  }
}

}  // namespace reftrack::app
