#pragma once
// `--stats F.csv`: one row per frame — its tracking state, the rejection's
// sets |Z| |Q| |Q->P| |P|, flow, times, the judgement against the
// simulator's truth (zeros on real data) and how the tracker found its pose.
#include <string>

#include "common/staged_file.h"
#include "tools/runner/frame_observer.h"

namespace depot::runner {

class StatsTable : public FrameObserver {
 public:
  // Stages `path` and writes the header; the file appears on commit().
  explicit StatsTable(const std::string& path);
  void on_frame(const FrameRecord& frame) override;
  void commit() override { file_.commit(); }

 private:
  StagedFile file_;
};

}  // namespace depot::runner
