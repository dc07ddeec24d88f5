#pragma once
// `--keypoints F.csv` (eval/keypoint_file.h): one row per keypoint of every
// frame — where it is, its set and decision, its depth and, on simulated
// data, whether it lies on a moving object or its boundary (MotionTruth's
// rule) and the instance there; empty truth columns on real data.
#include <string>

#include "common/staged_file.h"
#include "tools/runner/frame_observer.h"

namespace depot::runner {

class KeypointRows : public FrameObserver {
 public:
  // Stages `path` and writes the header; the file appears on commit().
  // Frames need a rejection filter (the keypoints' sets are its).
  explicit KeypointRows(const std::string& path);
  void on_frame(const FrameRecord& frame) override;
  void commit() override { file_.commit(); }

 private:
  StagedFile file_;
};

}  // namespace depot::runner
