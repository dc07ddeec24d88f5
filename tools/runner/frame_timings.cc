#include "tools/runner/frame_timings.h"

#include "common/percentile.h"

namespace depot::runner {

void FrameTimings::on_frame(const FrameRecord& frame) {
  const slam::TrackResult& r = frame.result;
  // A frame that follows a lost one is where relocalisation is tried.
  if (previous_ == slam::TrackingState::kLost) relocalising_.push_back(r.timing.track_ms);
  previous_ = r.state;
  lost_ += r.state == slam::TrackingState::kLost;
  relocalized_ += r.state == slam::TrackingState::kRelocalized;
  total_.push_back(r.timing.total_ms);
  extract_.push_back(r.timing.extract_ms);
  track_.push_back(r.timing.track_ms);
  if (!frame.filter) return;
  filter_.push_back(frame.rejection.filter_ms);
  wait_.push_back(frame.rejection.wait_ms);
  detect_.push_back(frame.rejection.detect_ms);
  flow_.push_back(frame.rejection.flow_ms);
}

void FrameTimings::on_finish(const slam::System&, const slam::RgbdSequence&, RunSummary& summary) {
  add_to(summary);
}

void FrameTimings::add_to(RunSummary& summary) const {
  summary.lost = lost_;
  summary.relocalized = relocalized_;
  summary.median_ms = percentile(total_, 0.5);
  summary.p95_ms = percentile(total_, 0.95);
  summary.extract_ms = percentile(extract_, 0.5);
  summary.track_ms = percentile(track_, 0.5);
  summary.filter_ms = percentile(filter_, 0.5);
  summary.wait_ms = percentile(wait_, 0.5);
  summary.wait_p95_ms = percentile(wait_, 0.95);
  summary.detect_ms = percentile(detect_, 0.5);
  summary.flow_ms = percentile(flow_, 0.5);
  summary.lost_ms = relocalising_.empty() ? 0 : percentile(relocalising_, 0.5);
}

}  // namespace depot::runner
