#include "sim/world/camera_clearance.h"

#include <cstdio>

#include "common/error.h"
#include "common/number_text.h"

namespace depot::sim {
namespace {

std::string frames_text(int first, int last) {
  return first == last ? std::to_string(first) : std::to_string(first) + "-" + std::to_string(last);
}

}  // namespace

double required_clearance(const Scenario& s) {
  return s.motion.clearance >= 0.0 ? s.motion.clearance : s.sensor.min_depth;
}

CameraClearance measure_camera_clearance(
    const Scenario& scenario, const StaticObstacles& obstacles, const CameraMotion& motion,
    const std::vector<std::pair<double, double>>& frame_stamps) {
  CameraClearance out;
  out.required = required_clearance(scenario);
  for (size_t i = 0; i < frame_stamps.size(); ++i) {
    const int frame = static_cast<int>(i);
    const Nearest n = obstacles.nearest(motion.pose_at(frame_stamps[i].first).translation());
    if (n.distance < out.nearest.distance) {
      out.nearest = n;
      out.frame = frame;
    }
    if (n.distance >= out.required) continue;
    if (out.too_close.empty() || out.too_close.back().last != frame - 1)
      out.too_close.push_back({frame, frame, frame, n});
    TooCloseRange& range = out.too_close.back();
    range.last = frame;
    if (n.distance < range.nearest.distance) {
      range.nearest = n;
      range.nearest_frame = frame;
    }
  }
  return out;
}

std::string describe_too_close(const CameraClearance& c) {
  constexpr size_t kShown = 8;
  std::string text =
      c.too_close.size() == 1 && c.too_close[0].first == c.too_close[0].last ? "frame " : "frames ";
  for (size_t i = 0; i < c.too_close.size() && i < kShown; ++i) {
    const TooCloseRange& r = c.too_close[i];
    const std::string where = r.nearest.distance <= 0.0
                                  ? "inside " + r.nearest.object
                                  : metres_text(r.nearest.distance) + " from " + r.nearest.object;
    text += (i ? ", " : "") + frames_text(r.first, r.last) + " (" + where +
            (r.first == r.last ? ")" : " at frame " + std::to_string(r.nearest_frame) + ")");
  }
  if (c.too_close.size() > kShown)
    text += " and " + std::to_string(c.too_close.size() - kShown) + " more ranges";
  return text;
}

void enforce_camera_clearance(const Scenario& s, const CameraClearance& c) {
  if (c.too_close.empty()) return;
  const std::string source =
      s.motion.clearance >= 0.0 ? "motion.clearance" : "the sensor's min_depth";
  const std::string problem = "the camera comes closer than " + metres_text(c.required) + " (" +
                              source + ") to the static scene at " + describe_too_close(c);
  if (!s.motion.allow_close)
    fail(s.source_path, problem + "; move the camera path away, or set motion.allow_close: true");
  std::fprintf(stderr, "depot: warning: %s: %s; rendering anyway (motion.allow_close)\n",
               s.source_path.c_str(), problem.c_str());
}

}  // namespace depot::sim
