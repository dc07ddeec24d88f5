#pragma once
// The run's times per frame as medians and p95 (RunSummary's *_ms), and its
// lost and relocalised frames.
#include <vector>

#include "tools/runner/frame_observer.h"

namespace depot::runner {

class FrameTimings : public FrameObserver {
 public:
  void on_frame(const FrameRecord& frame) override;
  void on_finish(const slam::System& system, const slam::RgbdSequence& sequence,
                 RunSummary& summary) override;
  // The figures so far into `summary` (on_finish's work).
  void add_to(RunSummary& summary) const;

 private:
  std::vector<double> total_, extract_, track_;
  std::vector<double> filter_, wait_, detect_, flow_;  // frames with a rejection filter
  std::vector<double> relocalising_;  // tracking times of frames that follow a lost one
  slam::TrackingState previous_ = slam::TrackingState::kNotInitialized;
  int lost_ = 0, relocalized_ = 0;
};

}  // namespace depot::runner
