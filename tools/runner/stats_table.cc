#include "tools/runner/stats_table.h"

#include <fmt/format.h>

#include "tools/runner/frame_truth.h"

namespace depot::runner {

StatsTable::StatsTable(const std::string& path) : file_(path) {
  file_.stream()
      << "frame,timestamp,state,keypoints,kept,Z,Q,Q_to_P,P,detections,flow_u,flow_v,z,wait_ms,"
         "detect_ms,flow_ms,"
         "filter_ms,total_ms,true_positive,false_positive,false_negative,false_positive_z,"
         "false_positive_q,method,matches,inliers,local_points,new_keyframe,motion_objects,"
         "motion_rejected\n";
}

void StatsTable::on_frame(const FrameRecord& frame) {
  const slam::TrackResult& r = frame.result;
  const slam::RejectionStats& rs = frame.rejection;
  static const FrameTruth kUnjudged;  // real data: zeros
  const FrameTruth& judged = frame.truth ? *frame.truth : kUnjudged;
  file_.stream() << fmt::format(
      "{},{:.6f},{},{},{},{},{},{},{},{},{:.3f},{:.3f},{:.3f},{:.2f},{:.2f},{:.2f},{:.2f},{:.2f},"
      "{},{},{},{},{},{},{},{},{},{},{},{}\n",
      frame.index, frame.timestamp, slam::tracking_state_name(r.state), rs.total, rs.kept, rs.z,
      rs.q, rs.q_to_p, rs.p, rs.detections, rs.mean_flow.x, rs.mean_flow.y, rs.z_threshold,
      rs.wait_ms, rs.detect_ms, rs.flow_ms, rs.filter_ms, r.timing.total_ms,
      judged.score.true_positive, judged.score.false_positive, judged.score.false_negative,
      judged.false_positive_z, judged.false_positive_q, slam::tracking_method_name(r.stats.method),
      r.stats.matches, r.stats.inliers, r.stats.local_points, r.stats.new_keyframe ? 1 : 0,
      rs.motion_objects, rs.motion_rejected);
}

}  // namespace depot::runner
