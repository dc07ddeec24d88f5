#include "tools/harness/schedule/sweep_progress.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>

#include "tools/harness/plan/run_record.h"

namespace depot::harness {
namespace {

double tracked_percent(const RunRecord& r) {
  return r.frames ? 100.0 * r.tracked / r.frames : NAN;
}

}  // namespace

std::string describe_finished_job(const SweepJob& job, const SweepLayout& layout) {
  if (job.kind == JobKind::kRender) {
    const DatasetRecord d = read_dataset_record(layout.dataset_record(job.id));
    return fmt::format("rendered {}: {} frames, {:.1f} % moving pixels", job.id, d.frames,
                       100 * d.moving_share_mean);
  }
  const RunRecord r = read_run_record(layout.run_record(job.id));
  if (!r.ok) return fmt::format("{}: no trajectory ({})", job.id, r.error);
  if (std::isfinite(r.precision))
    return fmt::format(
        "{}: ATE {:.4f} m, precision {:.2f} (boundary static {:.2f}) recall {:.2f}, tracked {:.1f} "
        "%, lost {}",
        job.id, r.ate_rmse, r.precision_without_boundary, r.precision, r.recall, tracked_percent(r),
        r.lost);
  return fmt::format("{}: ATE {:.4f} m, tracked {:.1f} %, lost {}", job.id, r.ate_rmse,
                     tracked_percent(r), r.lost);
}

SweepProgress::SweepProgress(size_t total, bool enabled) : total_(total), enabled_(enabled) {}

double SweepProgress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void SweepProgress::started(const std::string& job_id, const std::string& extra) const {
  if (!enabled_) return;
  std::fprintf(stderr, "sweep: [%zu/%zu] started %s  (%.0f s elapsed%s)\n", done_, total_,
               job_id.c_str(), elapsed(), extra.c_str());
}

void SweepProgress::finished(const std::string& line) {
  ++done_;
  if (!enabled_) return;
  const double seconds = elapsed();
  const double eta = seconds / done_ * (total_ - done_);
  std::fprintf(stderr, "sweep: [%zu/%zu] %s  (%.0f s elapsed, about %.0f s left)\n", done_, total_,
               line.c_str(), seconds, eta);
}

}  // namespace depot::harness
