#include "slam/system/system.h"

#include <algorithm>
#include <chrono>
#include <map>

#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "slam/io/map_file.h"
#include "slam/place/vocabulary_file.h"

namespace depot::slam {
namespace {

double ms_between(std::chrono::steady_clock::time_point a,
                  std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Camera pose of a trajectory entry, following culled references up the
// spanning tree (ORB-SLAM2's way of letting corrections reach every frame);
// the keyframe it ends at names the entry's map. Null without a reference.
const KeyFrame* resolve(const TrajectoryEntry& e, Pose& T_wc) {
  KeyFrame* ref = e.reference;
  if (!ref) return nullptr;
  Pose T_cr = e.T_cr;
  while (ref->bad && ref->parent()) {
    T_cr = T_cr * ref->T_cp;
    ref = ref->parent();
  }
  T_wc = (T_cr * ref->T_cw).inverse();
  return ref;
}

// The atlas maps of the tracked frames numbered by the frames each holds,
// most first (the older on a tie): 0 is the main map. Caller holds the map lock.
std::map<int, int> map_numbers(const std::vector<TrajectoryEntry>& entries) {
  std::map<int, size_t> frames;
  for (const TrajectoryEntry& e : entries) {
    Pose T_wc;
    if (!is_tracked(e.state)) continue;
    if (const KeyFrame* ref = resolve(e, T_wc)) ++frames[ref->map_id];
  }
  std::vector<std::pair<int, size_t>> by_size(frames.begin(), frames.end());
  std::stable_sort(by_size.begin(), by_size.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  std::map<int, int> numbers;
  for (size_t i = 0; i < by_size.size(); ++i) numbers[by_size[i].first] = static_cast<int>(i);
  return numbers;
}

// The atlas map holding most tracked frames, -1 when none is tracked.
int main_map(const std::vector<TrajectoryEntry>& entries) {
  for (const auto& [id, number] : map_numbers(entries))
    if (number == 0) return id;
  return -1;
}

}  // namespace

System::System(const SlamSettings& settings, KeypointFilter* filter)
    : settings_(settings),
      filter_(filter),
      levels_(ScaleLevels::make(settings.orb.n_levels, settings.orb.scale_factor)),
      extractor_(settings.orb),
      places_(load_vocabulary_shared(settings.vocabulary.empty() ? default_vocabulary_path()
                                                                 : settings.vocabulary)),
      mapper_(map_, settings.threaded_mapping, &places_),
      loop_closer_(map_, places_, mapper_, settings.threaded_mapping, settings.loop_closer),
      tracker_(map_, mapper_, settings.tracker, &places_) {
  if (settings.loop_closing) mapper_.set_next(&loop_closer_);
}

System::~System() {
  mapper_.stop();
  loop_closer_.stop();
}

void System::check_workers() const {
  if (std::exception_ptr e = loop_closer_.failure()) {
    try {
      std::rethrow_exception(e);
    } catch (const std::exception& ex) {
      fail("loop closing", ex.what());
    }
  }
}

void System::check_images(const cv::Mat& bgr, const cv::Mat& depth, long frame_id) const {
  const PinholeCamera& cam = settings_.camera;
  if (bgr.type() != CV_8UC3 || bgr.cols != cam.width || bgr.rows != cam.height)
    fail("frame " + std::to_string(frame_id), "colour image must be CV_8UC3 of the camera's size");
  if (depth.type() != CV_32F || depth.size() != bgr.size())
    fail("frame " + std::to_string(frame_id),
         "depth must be CV_32F metres of the colour image's size");
}

void System::look_ahead(const cv::Mat& bgr, const cv::Mat& depth, double timestamp) {
  const long id = next_frame_id_ + static_cast<long>(ahead_.size());
  check_images(bgr, depth, id);
  ahead_.push_back(timestamp);
  const cv::Mat no_gray;  // made when the frame is tracked
  if (filter_)
    filter_->look_ahead(FrameImages{bgr, no_gray, depth, timestamp, id, &settings_.camera});
}

TrackResult System::track(const cv::Mat& bgr, const cv::Mat& depth, double timestamp) {
  mapper_.throw_if_failed();
  const PinholeCamera& cam = settings_.camera;
  check_images(bgr, depth, next_frame_id_);
  if (!ahead_.empty()) {
    if (ahead_.front() != timestamp)
      fail("frame " + std::to_string(next_frame_id_),
           "track() got timestamp " + std::to_string(timestamp) + " but look_ahead() handed over " +
               std::to_string(ahead_.front()) +
               " for this frame (frames must be tracked in the order handed over)");
    ahead_.pop_front();
  }
  TrackResult result;
  auto t0 = std::chrono::steady_clock::now();
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  if (filter_) filter_->begin_frame(FrameImages{bgr, gray, depth, timestamp, next_frame_id_, &cam});
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  extractor_.extract(gray, cv::Mat(), keypoints, descriptors);
  auto t1 = std::chrono::steady_clock::now();
  result.keypoints = static_cast<int>(keypoints.size());
  if (filter_) {
    std::vector<uint8_t> keep(keypoints.size(), 1);
    filter_->filter(FrameImages{bgr, gray, depth, timestamp, next_frame_id_, &cam}, keypoints,
                    keep);
    std::vector<cv::KeyPoint> kept;
    cv::Mat kept_desc;
    for (size_t i = 0; i < keypoints.size(); ++i) {
      if (!keep[i]) continue;
      kept.push_back(keypoints[i]);
      kept_desc.push_back(descriptors.row(static_cast<int>(i)));
    }
    keypoints.swap(kept);
    descriptors = kept_desc;
  }
  auto t2 = std::chrono::steady_clock::now();
  result.kept = static_cast<int>(keypoints.size());
  Frame frame(next_frame_id_++, timestamp,
              Features(std::move(keypoints), descriptors, depth, cam, &levels_));
  frame.features.set_colours(bgr);
  result.state = tracker_.track(std::move(frame), &result.stats);
  if (!settings_.threaded_mapping) {
    mapper_.run_pending();
    loop_closer_.run_pending();
  }
  check_workers();
  if (tracker_.wants_reset()) {
    // Lost right after start: begin a new map (ORB-SLAM2 does the same). The
    // frames tracked in the old map become ABANDONED.
    mapper_.reset();
    loop_closer_.reset();
    MutexLock lock(map_.mutex());
    tracker_.map_mutex().assert_held();  // the tracker's map is map_
    if (settings_.tracker.atlas) {
      tracker_.discard_active_map();  // the atlas's other maps stay
    } else {
      map_.clear();
      places_.clear();
      tracker_.reset();
    }
    ++resets_;
  }
  auto t3 = std::chrono::steady_clock::now();
  if (result.state == TrackingState::kOk || result.state == TrackingState::kRelocalized) {
    MutexLock lock(map_.mutex());
    result.T_wc = tracker_.last_frame().T_cw.inverse();
  }
  result.timing = {ms_between(t0, t1), ms_between(t1, t2), ms_between(t2, t3), ms_between(t0, t3)};
  return result;
}

void System::finish() {
  if (settings_.threaded_mapping) {
    // Wait until the queue is empty and the mapper idle.
    while (!mapper_.idle() || !loop_closer_.idle())
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
  } else {
    mapper_.run_pending();
    loop_closer_.run_pending();
  }
  mapper_.throw_if_failed();
  check_workers();
}

void System::load_map(const std::string& path) {
  if (next_frame_id_ > 0) fail(path, "a map can only be loaded before the first frame");
  MutexLock lock(map_.mutex());
  load_map_file(path, settings_.camera, levels_, vocabulary_identity(places_.vocabulary()), map_);
  for (KeyFrame* kf : map_.keyframes()) {
    places_.describe(*kf);
    places_.add(kf);
  }
  tracker_.map_mutex().assert_held();  // the tracker's map is map_
  tracker_.relocalise_in_map();
}

void System::save_map(const std::string& path) const {
  MutexLock lock(map_.mutex());
  if (map_.n_keyframes() == 0) fail(path, "no map to save: no frame was tracked");
  // Every map of the atlas, each in its own frame.
  save_map_file(map_, settings_.camera, levels_, vocabulary_identity(places_.vocabulary()), path);
}

void System::start_localisation() {
  finish();
  MutexLock lock(map_.mutex());
  if (map_.n_keyframes() == 0)
    fail("localisation only", "there is no map to localise in (load one with --load-map)");
  tracker_.set_localisation_only(true);
  tracker_.map_mutex().assert_held();  // the tracker's map is map_
  tracker_.relocalise_in_map();
}

std::vector<StampedPose> System::trajectory() const {
  MutexLock lock(map_.mutex());
  const int main = main_map(tracker_.trajectory());
  std::vector<StampedPose> out;
  for (const TrajectoryEntry& e : tracker_.trajectory()) {
    Pose T_wc;
    if (!is_tracked(e.state)) continue;
    const KeyFrame* ref = resolve(e, T_wc);
    if (ref && ref->map_id == main) out.push_back({e.timestamp, T_wc});
  }
  return out;
}

std::vector<StampedFrameState> System::frame_states() const {
  MutexLock lock(map_.mutex());
  const std::map<int, int> numbers = map_numbers(tracker_.trajectory());
  std::vector<StampedFrameState> out;
  for (const TrajectoryEntry& e : tracker_.trajectory()) {
    StampedFrameState f{e.timestamp, e.state, -1};
    Pose T_wc;
    if (is_tracked(f.state)) {
      const KeyFrame* ref = resolve(e, T_wc);
      f.map = ref ? numbers.at(ref->map_id) : -1;
      if (f.map != 0) f.state = FrameState::kOtherMap;
    }
    out.push_back(f);
  }
  return out;
}

std::vector<AtlasPose> System::atlas_trajectory() const {
  MutexLock lock(map_.mutex());
  const std::map<int, int> numbers = map_numbers(tracker_.trajectory());
  std::vector<AtlasPose> out;
  for (const TrajectoryEntry& e : tracker_.trajectory()) {
    Pose T_wc;
    if (!is_tracked(e.state)) continue;
    if (const KeyFrame* ref = resolve(e, T_wc))
      out.push_back({{e.timestamp, T_wc}, numbers.at(ref->map_id)});
  }
  return out;
}

std::vector<StampedPose> System::keyframe_trajectory() const {
  std::vector<std::vector<StampedPose>> maps = keyframe_trajectories();
  return maps.empty() ? std::vector<StampedPose>{} : std::move(maps.front());
}

std::vector<std::vector<StampedPose>> System::keyframe_trajectories() const {
  MutexLock lock(map_.mutex());
  const std::map<int, int> numbers = map_numbers(tracker_.trajectory());
  std::vector<std::vector<StampedPose>> out(numbers.size());
  for (KeyFrame* kf : map_.keyframes()) {
    const auto number = numbers.find(kf->map_id);
    if (!kf->bad && number != numbers.end())
      out[number->second].push_back({kf->timestamp, kf->T_cw.inverse()});
  }
  return out;
}

int System::maps() const {
  MutexLock lock(map_.mutex());
  return static_cast<int>(map_.map_ids().size());
}

size_t System::n_keyframes() const {
  MutexLock lock(map_.mutex());
  return map_.n_keyframes();
}

size_t System::n_map_points() const {
  MutexLock lock(map_.mutex());
  return map_.n_map_points();
}

}  // namespace depot::slam
