#include "slam/reject/rejection_filter.h"

#include <chrono>

#include "common/error.h"

namespace depot::slam {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

RejectionMode parse_rejection_mode(const std::string& name) {
  if (name == "orb") return RejectionMode::kOrb;
  if (name == "orb+yolo") return RejectionMode::kOrbYolo;
  if (name == "orb+lk") return RejectionMode::kOrbLk;
  if (name == "full") return RejectionMode::kFull;
  fail("--mode", "unknown mode '" + name + "' (expected orb, orb+yolo, orb+lk, full)");
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
  }
  return "orb";
}

bool mode_uses_detector(RejectionMode m) {
  return m == RejectionMode::kOrbYolo || m == RejectionMode::kFull;
}
bool mode_uses_flow(RejectionMode m) {
  return m == RejectionMode::kOrbLk || m == RejectionMode::kFull;
}

RejectionFilter::RejectionFilter(RejectionMode mode, AprioriClasses classes, Detector* detector,
                                 const RejectionParams& params)
    : mode_(mode),
      classes_(std::move(classes)),
      detector_(detector),
      params_(params),
      flow_(params.flow) {
  if (mode_uses_detector(mode_)) {
    if (!detector_) fail(rejection_mode_name(mode_), "this mode needs a detector");
    thread_ = std::make_unique<DetectionThread>(*detector_);
  }
}

void RejectionFilter::begin_frame(const FrameImages& images) {
  if (thread_) thread_->submit(images.bgr, images.timestamp, images.frame_id);
}

void RejectionFilter::filter(const FrameImages& images, const std::vector<cv::KeyPoint>& keypoints,
                             std::vector<uint8_t>& keep) {
  stats_ = RejectionStats();
  stats_.frame = images.frame_id;
  stats_.total = static_cast<int>(keypoints.size());
  detections_.clear();
  if (thread_) detections_ = thread_->wait(&stats_.wait_ms, &stats_.detect_ms);
  const auto t0 = std::chrono::steady_clock::now();
  stats_.detections = static_cast<int>(detections_.size());
  keep.assign(keypoints.size(), 1);
  sets_.assign(keypoints.size(), PointSet::kP);

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
    case RejectionMode::kFull: {
      std::vector<PointSet> sets = assign_point_sets(keypoints, detections_, classes_);
      if (params_.background_depth_margin > 0) {
        std::vector<float> depth(keypoints.size(), 0.0f);
        for (size_t i = 0; i < keypoints.size(); ++i) {
          const int x = static_cast<int>(keypoints[i].pt.x + 0.5f),
                    y = static_cast<int>(keypoints[i].pt.y + 0.5f);
          if (x >= 0 && y >= 0 && x < images.depth.cols && y < images.depth.rows)
            depth[i] = images.depth.at<float>(y, x);
        }
        move_background_to_q(keypoints, depth, detections_, classes_,
                             params_.background_depth_margin, sets);
      }
      std::vector<size_t> q_index, p_sample;
      std::vector<size_t> p_index;
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
      if (!q_index.empty() && flow_.has_previous()) {
        // Flow only for Q and an even sample of P (enough for its mean).
        const auto tf = std::chrono::steady_clock::now();
        const size_t step = std::max<size_t>(1, p_index.size() / params_.max_reference_points);
        for (size_t k = 0; k < p_index.size(); k += step) p_sample.push_back(p_index[k]);
        std::vector<cv::Point2f> pts, flow;
        std::vector<uint8_t> ok;
        for (size_t i : p_sample) pts.push_back(keypoints[i].pt);
        for (size_t i : q_index) pts.push_back(keypoints[i].pt);
        flow_.flow(pts, flow, ok);
        const std::vector<cv::Point2f> p_flow(flow.begin(), flow.begin() + p_sample.size());
        const std::vector<uint8_t> p_ok(ok.begin(), ok.begin() + p_sample.size());
        const FlowTestResult test = mean_static_flow(p_flow, p_ok, params_.test);
        stats_.flow_ms += ms_since(tf);
        stats_.mean_flow = test.mean;
        stats_.z_threshold = test.z;
        for (size_t k = 0; k < q_index.size(); ++k) {
          const size_t j = p_sample.size() + k;
          // A Q point passes when it tracked and moves with the static scene.
          const bool passes = ok[j] && !flow_is_dynamic(flow[j], test);
          keep[q_index[k]] = passes;
          stats_.q_to_p += passes;
        }
      } else {
        stats_.q_to_p = stats_.q;  // no previous frame: nothing to test against
      }
      stats_.p = static_cast<int>(p_index.size()) + stats_.q_to_p;
      sets_ = sets;
      break;
    }
  }
  stats_.kept = 0;
  for (uint8_t k : keep) stats_.kept += k;
  stats_.filter_ms = ms_since(t0);
  keypoints_ = keypoints;
  keep_ = keep;
}

}  // namespace depot::slam
