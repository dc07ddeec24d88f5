#include "slam/reject/rejection_filter.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "common/error.h"
#include "slam/detect/nms.h"

namespace depot::slam {
namespace {

// An object made from motion-found keypoints, not a detector's box.
bool found_by_motion(const TrackedBox& object) {
  return object.detection.class_name == kMotionClass;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

RejectionMode parse_rejection_mode(const std::string& name) {
  if (name == "orb") return RejectionMode::kOrb;
  if (name == "orb+yolo") return RejectionMode::kOrbYolo;
  if (name == "orb+lk") return RejectionMode::kOrbLk;
  if (name == "full") return RejectionMode::kFull;
  if (name == "masked") return RejectionMode::kMasked;
  fail("--mode", "unknown mode '" + name + "' (expected orb, orb+yolo, orb+lk, full, masked)");
}

RejectionParams::PersonMask parse_person_mask(const std::string& name, const std::string& where) {
  if (name == "depth") return RejectionParams::PersonMask::kDepth;
  if (name == "segmentation") return RejectionParams::PersonMask::kSegmentation;
  if (name == "both") return RejectionParams::PersonMask::kBoth;
  fail(where, "unknown person mask source '" + name + "' (expected depth, segmentation, both)");
}

const char* rejection_mode_name(RejectionMode m) {
  switch (m) {
    case RejectionMode::kOrb:
      return "orb";
    case RejectionMode::kOrbYolo:
      return "orb+yolo";
    case RejectionMode::kOrbLk:
      return "orb+lk";
    case RejectionMode::kFull:
      return "full";
    case RejectionMode::kMasked:
      return "masked";
  }
  return "orb";
}

bool mode_uses_detector(RejectionMode m) {
  return m == RejectionMode::kOrbYolo || m == RejectionMode::kFull || m == RejectionMode::kMasked;
}
bool mode_uses_flow(RejectionMode m) {
  return m == RejectionMode::kOrbLk || m == RejectionMode::kFull || m == RejectionMode::kMasked;
}

RejectionFilter::RejectionFilter(RejectionMode mode, AprioriClasses classes, Detector* detector,
                                 const RejectionParams& params)
    : mode_(mode),
      classes_(std::move(classes)),
      detector_(detector),
      params_(params),
      box_tracker_(params.tracking),
      flow_(params.flow) {
  if (mode_uses_detector(mode_)) {
    if (!detector_) fail(rejection_mode_name(mode_), "this mode needs a detector");
    thread_ = std::make_unique<DetectionThread>(*detector_);
  }
}

void RejectionFilter::set_segmenter(PersonSegmenter* segmenter) {
  if (mode_ == RejectionMode::kMasked && params_.person_mask != RejectionParams::PersonMask::kDepth)
    thread_ = std::make_unique<DetectionThread>(*detector_, 4, segmenter);
}

void RejectionFilter::begin_frame(const FrameImages& images) {
  if (thread_) thread_->submit(images.bgr, images.timestamp, images.frame_id);  // no-op if ahead
}

void RejectionFilter::look_ahead(const FrameImages& next) {
  if (thread_) thread_->submit(next.bgr, next.timestamp, next.frame_id);
}

void RejectionFilter::filter(const FrameImages& images, const std::vector<cv::KeyPoint>& keypoints,
                             std::vector<uint8_t>& keep) {
  stats_ = RejectionStats();
  stats_.frame = images.frame_id;
  stats_.total = static_cast<int>(keypoints.size());
  detections_.clear();
  if (thread_)
    detections_ = thread_->wait(images.frame_id, &stats_.wait_ms, &stats_.detect_ms, &person_mask_,
                                &stats_.segment_ms);
  const auto t0 = std::chrono::steady_clock::now();
  stats_.detections = static_cast<int>(detections_.size());
  keep.assign(keypoints.size(), 1);
  sets_.assign(keypoints.size(), PointSet::kP);
  dynamic_object_.clear();

  if (mode_uses_flow(mode_)) {
    const auto tf = std::chrono::steady_clock::now();
    flow_.next_frame(images.gray);
    stats_.flow_ms += ms_since(tf);
  }

  switch (mode_) {
    case RejectionMode::kOrb:
      stats_.p = stats_.total;
      break;
    case RejectionMode::kOrbYolo: {
      const std::vector<bool> inside = inside_dynamic_boxes(keypoints, detections_, classes_);
      for (size_t i = 0; i < keypoints.size(); ++i) {
        keep[i] = !inside[i];
        (inside[i] ? stats_.z : stats_.p)++;
        if (inside[i]) sets_[i] = PointSet::kZ;
      }
      break;
    }
    case RejectionMode::kOrbLk: {
      // The flow test on every point, against the mean flow of all points.
      if (!flow_.has_previous()) {
        stats_.p = stats_.total;
        break;
      }
      const auto tf = std::chrono::steady_clock::now();
      std::vector<cv::Point2f> pts, flow;
      std::vector<uint8_t> ok;
      for (const auto& kp : keypoints) pts.push_back(kp.pt);
      flow_.flow(pts, flow, ok);
      const FlowTestResult test = mean_static_flow(flow, ok, params_.test);
      stats_.flow_ms += ms_since(tf);
      stats_.mean_flow = test.mean;
      stats_.z_threshold = test.z;
      for (size_t i = 0; i < keypoints.size(); ++i) {
        keep[i] = !(ok[i] && flow_is_dynamic(flow[i], test));
        (keep[i] ? stats_.p : stats_.z)++;
      }
      break;
    }
    case RejectionMode::kFull:
      filter_full(images, keypoints, keep);
      break;
    case RejectionMode::kMasked: {
      std::vector<float> depth;  // only the camera-motion flow test reads it
      if ((params_.ego_motion_flow || params_.motion.enabled) && images.camera)
        depth = keypoint_depths(images.depth, keypoints);
      sets_ = masked_sets(images, keypoints);
      decide_sets(images, keypoints, depth, keep);
      break;
    }
  }
  stats_.kept = 0;
  for (uint8_t k : keep) stats_.kept += k;
  stats_.filter_ms = ms_since(t0);
  keypoints_ = keypoints;
  keep_ = keep;
}

cv::Mat RejectionFilter::moving_mask(cv::Size image) const {
  if (mode_ == RejectionMode::kOrb || mode_ == RejectionMode::kOrbLk)
    fail(rejection_mode_name(mode_), "rejects keypoints, not pixels: it has no moving mask");
  cv::Mat mask = cv::Mat::zeros(image, CV_8U);
  const cv::Rect frame(cv::Point(0, 0), image);
  // A potentially dynamic object moves when the flow test rejected most of
  // the Q keypoints on it.
  auto flow_says_moving = [&](auto&& on_object) {
    int rejected = 0, kept = 0;
    for (size_t i = 0; i < keypoints_.size(); ++i) {
      if (sets_[i] != PointSet::kQ || !on_object(keypoints_[i])) continue;
      (keep_[i] ? kept : rejected)++;
    }
    return rejected > 0 && rejected >= kept;
  };
  auto paint_box = [&](const cv::Rect2f& box) { mask(cv::Rect(box) & frame).setTo(255); };
  if (mode_ == RejectionMode::kMasked) {
    for (size_t k = 0; k < objects_.size(); ++k) {
      const Detection& d = objects_[k].detection;
      const ObjectMask& object = masks_[k];
      const bool dynamic = object_class(objects_[k]) == MotionClass::kDynamic;
      if (!dynamic && !flow_says_moving([&](const cv::KeyPoint& kp) {
            return object.valid() ? object.touches(kp, params_.scale_factor, params_.mask_reach)
                                  : d.box.contains(kp.pt);
          }))
        continue;
      if (object.valid())
        mask(object.region).setTo(255, object.mask);
      else
        paint_box(d.box);
    }
    return mask;
  }
  for (const Detection& d : detections_) {
    const MotionClass motion = classes_.classify(d.class_name);
    if (motion == MotionClass::kDynamic ||
        (motion == MotionClass::kPotentiallyDynamic && mode_ == RejectionMode::kFull &&
         flow_says_moving([&](const cv::KeyPoint& kp) { return d.box.contains(kp.pt); })))
      paint_box(d.box);
  }
  return mask;
}

void RejectionFilter::filter_full(const FrameImages& images,
                                  const std::vector<cv::KeyPoint>& keypoints,
                                  std::vector<uint8_t>& keep) {
  std::vector<PointSet> sets = assign_point_sets(keypoints, detections_, classes_);
  const bool ego = params_.ego_motion_flow && images.camera;
  std::vector<float> depth;
  if (params_.background_depth_margin > 0 || ego) depth = keypoint_depths(images.depth, keypoints);
  if (params_.background_depth_margin > 0)
    split_boxes_by_depth(keypoints, depth, detections_, classes_, params_.background_depth_margin,
                         sets);
  sets_ = std::move(sets);
  decide_sets(images, keypoints, depth, keep);
}

std::vector<PointSet> RejectionFilter::masked_sets(const FrameImages& images,
                                                   const std::vector<cv::KeyPoint>& keypoints) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<Detection> movable;  // dynamic and potentially dynamic objects
  for (const Detection& d : detections_)
    if (classes_.classify(d.class_name) != MotionClass::kStatic) movable.push_back(d);
  movable.insert(movable.end(), motion_detections_.begin(), motion_detections_.end());
  motion_detections_.clear();
  if (params_.carry_by_flow) move_tracks_by_flow();
  objects_ = box_tracker_.update(movable);
  // A motion-found object is found again while it moves; one not found is
  // still or gone, and is not carried on.
  objects_.erase(std::remove_if(objects_.begin(), objects_.end(),
                                [](const TrackedBox& object) {
                                  return object.missed > 0 && found_by_motion(object);
                                }),
                 objects_.end());
  masks_.clear();
  const bool segment = !person_mask_.empty();
  for (TrackedBox& object : objects_) {
    // A carried box's object is looked for at the depth it had.
    ObjectMask mask = segment_object(images.depth, object.detection.box, params_.mask,
                                     images.camera, object.missed > 0 ? object.depth : 0.0f);
    if (mask.valid()) box_tracker_.set_depth(object.track_id, mask.depth);
    stats_.masks += mask.valid();
    if (segment && object.detection.class_name == "person") {
      mask = with_segmentation(mask, person_mask_, object.detection.box, params_.mask,
                               params_.person_mask == RejectionParams::PersonMask::kBoth);
    }
    if (object.missed > 0) {
      stats_.carried++;
      // Re-centre the carried box on its object, so drift does not build up.
      if (mask.valid()) {
        object.detection.box = mask.bounds();
        box_tracker_.correct(object.track_id, object.detection.box);
      }
    }
    masks_.push_back(std::move(mask));
  }

  std::vector<PointSet> object_sets;  // Z for dynamic objects, Q for potentially dynamic ones
  for (const TrackedBox& object : objects_)
    object_sets.push_back(object_class(object) == MotionClass::kDynamic ? PointSet::kZ
                                                                        : PointSet::kQ);
  std::vector<PointSet> sets(keypoints.size(), PointSet::kP);
  std::vector<int> dynamic_object(keypoints.size(), -1);
  on_detected_object_.assign(keypoints.size(), 0);
  for (size_t i = 0; i < keypoints.size(); ++i) {
    const cv::KeyPoint& kp = keypoints[i];
    for (size_t k = 0; k < objects_.size() && sets[i] != PointSet::kZ; ++k) {
      const PointSet object_set = object_sets[k];
      const ObjectMask& mask = masks_[k];
      // A box whose object has no depth at all: the whole box, as the paper.
      const bool on_object = mask.valid()
                                 ? mask.touches(kp, params_.scale_factor, params_.mask_reach)
                                 : objects_[k].detection.box.contains(kp.pt);
      if (!on_object) continue;
      if (!found_by_motion(objects_[k])) on_detected_object_[i] = 1;
      sets[i] = std::max(sets[i], object_set);
      if (object_set == PointSet::kZ) dynamic_object[i] = static_cast<int>(k);
    }
  }
  if (params_.carry_by_flow) {
    // At most kFollowed keypoints of each object, spread over it.
    constexpr size_t kFollowed = 40;
    object_points_.clear();
    for (size_t k = 0; k < objects_.size(); ++k) {
      std::vector<cv::Point2f> on;
      for (const cv::KeyPoint& kp : keypoints) {
        const bool on_object = masks_[k].valid()
                                   ? masks_[k].on_object(cvRound(kp.pt.x), cvRound(kp.pt.y))
                                   : objects_[k].detection.box.contains(kp.pt);
        if (on_object) on.push_back(kp.pt);
      }
      std::vector<cv::Point2f> sample;
      const size_t step = std::max<size_t>(1, on.size() / kFollowed);
      for (size_t i = 0; i < on.size() && sample.size() < kFollowed; i += step)
        sample.push_back(on[i]);
      object_points_.emplace_back(objects_[k].track_id, std::move(sample));
    }
  }
  // The still-object test needs a previous frame's flow; without one a
  // dynamic object's keypoints stay in Z.
  dynamic_object_.clear();
  if (params_.still_object_max_moving > 0 && flow_.has_previous()) {
    for (size_t i = 0; i < keypoints.size(); ++i)
      if (dynamic_object[i] >= 0) sets[i] = PointSet::kQ;
    dynamic_object_ = std::move(dynamic_object);
  }
  stats_.mask_ms = ms_since(t0);
  return sets;
}

void RejectionFilter::move_tracks_by_flow() {
  constexpr size_t kMinFollowed = 4;
  if (flow_.has_previous()) {
    std::vector<cv::Point2f> now;
    std::vector<uint8_t> ok;
    for (const auto& [track_id, points] : object_points_) {
      flow_.follow(points, now, ok);
      std::vector<float> dx, dy;
      for (size_t i = 0; i < points.size(); ++i)
        if (ok[i]) {
          dx.push_back(now[i].x - points[i].x);
          dy.push_back(now[i].y - points[i].y);
        }
      if (dx.size() < kMinFollowed) continue;
      // The median: the object's bulk, not a swinging arm or a bad track.
      std::nth_element(dx.begin(), dx.begin() + dx.size() / 2, dx.end());
      std::nth_element(dy.begin(), dy.begin() + dy.size() / 2, dy.end());
      box_tracker_.set_motion(track_id, {dx[dx.size() / 2], dy[dy.size() / 2]});
    }
  }
  object_points_.clear();
}

void RejectionFilter::decide_sets(const FrameImages& images,
                                  const std::vector<cv::KeyPoint>& keypoints,
                                  const std::vector<float>& depth, std::vector<uint8_t>& keep) {
  const std::vector<PointSet>& sets = sets_;
  const bool ego = params_.ego_motion_flow && images.camera;
  std::vector<size_t> q_index, p_index;
  for (size_t i = 0; i < sets.size(); ++i) {
    if (sets[i] == PointSet::kZ) {
      keep[i] = 0;
      stats_.z++;
    } else if (sets[i] == PointSet::kQ) {
      q_index.push_back(i);
    } else {
      p_index.push_back(i);
    }
  }
  stats_.q = static_cast<int>(q_index.size());
  const bool test_p = params_.test_static_points;
  // Movers without a detection: every point with depth outside a detector's
  // object is tested against the camera's motion too.
  const bool find_movers =
      mode_ == RejectionMode::kMasked && params_.motion.enabled && images.camera;
  const bool fit = ego || find_movers;
  if ((q_index.empty() && !test_p && !find_movers) || !flow_.has_previous()) {
    stats_.q_to_p = stats_.q;  // nothing to test, or no previous frame to test against
    stats_.p = static_cast<int>(p_index.size()) + stats_.q_to_p;
    return;
  }
  // Flow only for Q and a sample of P (enough for its mean or motion), or for
  // all of P when P is tested too.
  const auto tf = std::chrono::steady_clock::now();
  std::vector<size_t> reference;
  const size_t wanted =
      std::max(1, fit ? 3 * params_.max_reference_points : params_.max_reference_points);
  const size_t step = test_p || find_movers ? 1 : std::max<size_t>(1, p_index.size() / wanted);
  for (size_t k = 0; k < p_index.size(); k += step) reference.push_back(p_index[k]);
  std::vector<cv::Point2f> pts, flow;
  std::vector<uint8_t> ok;
  for (size_t i : reference) pts.push_back(keypoints[i].pt);
  for (size_t i : q_index) pts.push_back(keypoints[i].pt);
  flow_.flow(pts, flow, ok);
  const size_t n_ref = reference.size();
  const std::vector<cv::Point2f> ref_flow(flow.begin(), flow.begin() + n_ref);
  const std::vector<uint8_t> ref_ok(ok.begin(), ok.begin() + n_ref);
  const FlowTestResult test = mean_static_flow(ref_flow, ref_ok, params_.test);
  EgoMotionModel motion;
  if (fit) {
    std::vector<cv::Point2f> ref_pts(pts.begin(), pts.begin() + n_ref);
    std::vector<float> ref_depth;
    for (size_t i : reference) ref_depth.push_back(depth[i]);
    motion = fit_ego_motion(*images.camera, ref_pts, ref_depth, ref_flow, ref_ok, params_.ego);
  }
  stats_.mean_flow = test.mean;
  stats_.z_threshold = test.z;
  stats_.ego_motion = motion.valid;
  const float ego_threshold = fit ? scaled_px(params_.ego.threshold_px, *images.camera) : 0.0f;
  // With a camera motion, re-track each tested point from where a static
  // point would have been (small window, so a nearby moving occluder does
  // not drag it); it moves when LK fails there or settles away from the
  // prediction. Without one, the paper's Eq. 7 on the pyramidal flow.
  std::vector<uint8_t> guided_moves(pts.size(), 0), guided(pts.size(), 0);
  if (motion.valid) {
    std::vector<size_t> tested;
    std::vector<cv::Point2f> current, previous, near, far;
    for (size_t j = 0; j < pts.size(); ++j) {
      const size_t kp = j < n_ref ? reference[j] : q_index[j - n_ref];
      // Q (and P with test_p) by the camera-motion test; for movers, P and
      // the keypoints of motion-found objects (so they are found again).
      const bool on_motion_object = j >= n_ref && !dynamic_object_.empty() &&
                                    dynamic_object_[kp] >= 0 &&
                                    found_by_motion(objects_[dynamic_object_[kp]]);
      const bool by_ego = ego && (j >= n_ref || test_p);
      const bool for_movers = find_movers && depth[kp] > 0 && (j < n_ref || on_motion_object);
      if (!by_ego && !for_movers) continue;
      cv::Point2f a, b;
      if (!predict_static_previous(motion, *images.camera, pts[j], depth[kp],
                                   params_.ego.no_depth_min, &a, &b))
        continue;
      tested.push_back(j);
      current.push_back(pts[j]);
      previous.push_back(0.5f * (a + b));
      near.push_back(a);
      far.push_back(b);
    }
    std::vector<uint8_t> refined_ok;
    flow_.refine(current, previous, refined_ok, params_.ego.refine_window,
                 params_.ego.refine_levels, params_.ego.refine_max_error);
    for (size_t k = 0; k < tested.size(); ++k) {
      guided[tested[k]] = 1;
      guided_moves[tested[k]] =
          !refined_ok[k] || distance_to_prediction(previous[k], near[k], far[k]) > ego_threshold;
    }
  }
  stats_.flow_ms += ms_since(tf);  // flow, fit and guided re-tracking
  auto moves = [&](size_t j) {
    if (guided[j]) return guided_moves[j] != 0;
    return ok[j] && flow_is_dynamic(flow[j], test);
  };
  // masked: a dynamic object moves unless few of its tracked keypoints do,
  // by the test at a still camera's threshold (the floor): the paper's
  // threshold grows with the camera's speed, and under fast rotation a
  // walking person's flow would pass it.
  auto moves_at_floor = [&](size_t j) {
    if (guided[j]) return guided_moves[j] != 0;
    const cv::Point2f d = flow[j] - test.mean;
    return ok[j] && d.dot(d) > params_.test.z_floor * params_.test.z_floor;
  };
  std::vector<uint8_t> object_moves;
  if (!dynamic_object_.empty()) {
    std::vector<int> tracked(objects_.size(), 0), moving(objects_.size(), 0);
    for (size_t k = 0; k < q_index.size(); ++k) {
      const int object = dynamic_object_[q_index[k]];
      const size_t j = n_ref + k;
      if (object < 0 || !(guided[j] || ok[j])) continue;
      tracked[object]++;
      moving[object] += moves_at_floor(j);
    }
    object_moves.assign(objects_.size(), 1);
    for (size_t o = 0; o < objects_.size(); ++o) {
      // Too few tracked keypoints to tell: a detected object of a dynamic
      // class moves, a motion-found one (only motion made it an object) not.
      object_moves[o] = tracked[o] < params_.still_object_min_points
                            ? !found_by_motion(objects_[o])
                            : moving[o] >= params_.still_object_max_moving * tracked[o];
      stats_.still_objects += !object_moves[o];  // tracked points: a dynamic object
    }
  }
  for (size_t k = 0; k < q_index.size(); ++k) {
    const size_t i = q_index[k];
    const int object = dynamic_object_.empty() ? -1 : dynamic_object_[i];
    if (object >= 0 && object_moves[object]) {
      keep[i] = 0;  // on a moving dynamic object: Z after all
      sets_[i] = PointSet::kZ;
      stats_.q--;
      stats_.z++;
      continue;
    }
    const size_t j = n_ref + k;
    // A Q point passes when it tracked and moves with the static scene.
    const bool passes = (guided[j] || ok[j]) && !moves(j);
    keep[i] = passes;
    stats_.q_to_p += passes;
  }
  if (test_p)
    for (size_t k = 0; k < n_ref; ++k)
      if (moves(k)) {
        keep[reference[k]] = 0;
        stats_.p_rejected++;
      }
  int p_on_movers = 0;
  if (find_movers && motion.valid) {
    std::vector<int8_t> moving(keypoints.size(), -1);
    for (size_t j = 0; j < pts.size(); ++j)
      if (guided[j]) moving[j < n_ref ? reference[j] : q_index[j - n_ref]] = guided_moves[j];
    p_on_movers = reject_motion_objects(images, keypoints, depth, moving, keep);
  }
  stats_.p = static_cast<int>(p_index.size()) - stats_.p_rejected - p_on_movers + stats_.q_to_p;
}

MotionClass RejectionFilter::object_class(const TrackedBox& object) const {
  if (found_by_motion(object)) return MotionClass::kDynamic;
  return classes_.classify(object.detection.class_name);
}

int RejectionFilter::reject_motion_objects(const FrameImages& images,
                                           const std::vector<cv::KeyPoint>& keypoints,
                                           const std::vector<float>& depth,
                                           const std::vector<int8_t>& moving,
                                           std::vector<uint8_t>& keep) {
  const auto t0 = std::chrono::steady_clock::now();
  // What a detector's box holds is decided already (its object's outline
  // drags LK on the background around it, so the whole searched region is
  // left out); the rest is evidence.
  std::vector<cv::Rect> detected_regions;
  for (const TrackedBox& object : objects_)
    if (!found_by_motion(object))
      detected_regions.push_back(
          search_region(object.detection.box, images.gray.size(), params_.mask.grow));
  auto near_detected = [&](const cv::Point2f& p) {
    for (const cv::Rect& r : detected_regions)
      if (r.contains(cv::Point(static_cast<int>(p.x), static_cast<int>(p.y)))) return true;
    return false;
  };
  std::vector<TestedKeypoint> tested;
  for (size_t i = 0; i < keypoints.size(); ++i)
    if (moving[i] >= 0 && depth[i] > 0 && !near_detected(keypoints[i].pt))
      tested.push_back({keypoints[i].pt, depth[i], moving[i] == 1});
  const std::vector<MotionObject> found =
      find_motion_objects(tested, images.gray.size(), params_.motion);
  int p_rejected = 0;
  const size_t tracked_objects = objects_.size();
  for (const MotionObject& object : found) {
    ObjectMask mask =
        segment_object(images.depth, object.box, params_.mask, images.camera, object.depth);
    if (!mask.valid()) continue;
    const cv::Rect2f bounds = mask.bounds();
    Detection detection;
    detection.box = bounds;
    detection.class_name = kMotionClass;
    detection.confidence = 1.0f;
    motion_detections_.push_back(detection);  // the next frame's box for it
    stats_.motion_objects++;
    // One tracked from the last frame is that object found again: its
    // keypoints were decided by the still-object test, the rest of its mask
    // is rejected now. A new one only joins the next frame's boxes (a
    // single frame's group is often a slip of the camera-motion fit).
    bool tracked = false;
    for (size_t k = 0; k < tracked_objects && !tracked; ++k)
      tracked = found_by_motion(objects_[k]) &&
                iou(objects_[k].detection.box, bounds) >= params_.tracking.min_iou;
    if (!tracked && !params_.motion.reject_on_first_sight) continue;
    for (size_t i = 0; i < keypoints.size(); ++i) {
      if (!keep[i] || on_detected_object_[i] ||
          !mask.touches(keypoints[i], params_.scale_factor, params_.mask_reach))
        continue;
      keep[i] = 0;
      if (sets_[i] == PointSet::kP) {
        p_rejected++;
      } else {  // a Q point that passed the flow test
        stats_.q--;
        stats_.q_to_p--;
      }
      sets_[i] = PointSet::kZ;
      stats_.z++;
      stats_.motion_rejected++;
    }
    if (tracked) continue;
    TrackedBox box;
    box.detection = detection;
    box.depth = mask.depth;
    objects_.push_back(box);
    masks_.push_back(std::move(mask));
  }
  stats_.mask_ms += ms_since(t0);
  return p_rejected;
}

}  // namespace depot::slam
