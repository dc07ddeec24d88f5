#include "tools/runner/keypoint_rows.h"

#include "eval/keypoint_file.h"
#include "tools/runner/frame_truth.h"

namespace depot::runner {
namespace {

char set_letter(slam::PointSet set) {
  return set == slam::PointSet::kZ ? 'Z' : set == slam::PointSet::kQ ? 'Q' : 'P';
}

}  // namespace

KeypointRows::KeypointRows(const std::string& path) : file_(path) {
  eval::write_keypoint_header(file_.stream());
}

void KeypointRows::on_frame(const FrameRecord& frame) {
  const slam::RejectionFilter& filter = *frame.filter;
  const auto& keypoints = filter.last_keypoints();
  eval::WrittenKeypoint row;
  row.frame = frame.index;
  row.timestamp = frame.timestamp;
  for (size_t k = 0; k < keypoints.size(); ++k) {
    row.keypoint = keypoints[k];
    row.set = set_letter(filter.last_sets()[k]);
    row.kept = filter.last_keep()[k] != 0;
    row.depth_m = frame.keypoint_depths[k];
    if (frame.truth) {
      const eval::MotionTruth::KeypointTruth& t = frame.truth->labels;
      row.truth =
          eval::WrittenKeypoint::Truth{t.on_moving[k] != 0, t.boundary[k] != 0, t.instance[k]};
    }
    eval::write_keypoint_row(file_.stream(), row);
  }
}

}  // namespace depot::runner
