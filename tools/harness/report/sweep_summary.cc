#include "tools/harness/report/sweep_summary.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <utility>

#include "eval/improvement.h"
#include "tools/harness/plan/sweep_job_state.h"

namespace fs = std::filesystem;

namespace depot::harness {

MeanStd mean_std(const std::vector<double>& values) {
  MeanStd out;
  double sum = 0;
  for (double v : values)
    if (std::isfinite(v)) sum += v, ++out.count;
  if (out.count == 0) return out;
  out.mean = sum / out.count;
  double sq = 0;
  for (double v : values)
    if (std::isfinite(v)) sq += (v - out.mean) * (v - out.mean);
  out.std = std::sqrt(sq / out.count);
  return out;
}

namespace {

// (baseline, ours) of one figure on every seed where both are finite.
std::vector<std::pair<double, double>> paired_values(const CellModeSummary& baseline,
                                                     const CellModeSummary& ours,
                                                     double RunRecord::*figure) {
  std::vector<std::pair<double, double>> out;
  for (const auto& [seed, run] : ours.runs_by_seed) {
    auto it = baseline.runs_by_seed.find(seed);
    if (it == baseline.runs_by_seed.end()) continue;
    const double b = it->second.*figure, o = run.*figure;
    if (std::isfinite(b) && std::isfinite(o)) out.emplace_back(b, o);
  }
  return out;
}

}  // namespace

double paired_improvement(const CellModeSummary& baseline, const CellModeSummary& ours,
                          double RunRecord::*figure) {
  double sum_base = 0, sum_ours = 0;
  const auto pairs = paired_values(baseline, ours, figure);
  for (const auto& [b, o] : pairs) sum_base += b, sum_ours += o;
  if (pairs.empty() || sum_base <= 0) return NAN;
  const double n = static_cast<double>(pairs.size());
  return eval::improvement_percent(sum_base / n, sum_ours / n);
}

PairedDifference paired_difference(const CellModeSummary& baseline, const CellModeSummary& ours,
                                   double RunRecord::*figure) {
  std::vector<double> diffs;
  for (const auto& [b, o] : paired_values(baseline, ours, figure)) diffs.push_back(o - b);
  PairedDifference out;
  out.difference = mean_std(diffs);
  const double n = static_cast<double>(diffs.size());
  if (diffs.size() >= 2 && out.difference.std > 0) {
    const double sample_std = out.difference.std * std::sqrt(n / (n - 1));
    out.t = out.difference.mean / (sample_std / std::sqrt(n));
  }
  return out;
}

const CellModeSummary* SweepSummary::find(size_t cell, const std::string& mode) const {
  for (const auto& e : entries)
    if (e.cell == cell && e.mode == mode) return &e;
  return nullptr;
}

SweepSummary summarize_records(const SweepPlan& plan, const std::vector<RunRecord>& records) {
  SweepSummary summary;
  std::map<std::string, const SweepJob*> jobs;
  for (const auto& job : plan.jobs)
    if (job.kind == JobKind::kSlam) {
      jobs[job.id] = &job;
      ++summary.expected_runs;
    }
  std::map<std::pair<size_t, std::string>, std::vector<const RunRecord*>> groups;
  for (const auto& r : records) {
    auto it = jobs.find(r.id);
    if (it == jobs.end()) continue;  // not part of this plan
    for (size_t cell : it->second->cells) groups[{cell, r.mode}].push_back(&r);
    summary.runs.push_back(r);
  }
  for (size_t c = 0; c < plan.cells.size(); ++c)
    for (const auto& mode : plan.spec.modes) {
      CellModeSummary e;
      e.cell = c;
      e.mode = mode;
      std::vector<double> ate, ate_sd, rt, rt_sd, rr, rr_sd, p, pb, r, tracked, moving;
      std::vector<double> posed, maps, ate_all, pd, rd;
      for (const RunRecord* run : groups[{c, mode}]) {
        e.runs_by_seed[run->seed] = *run;
        ++e.runs;
        e.without_trajectory += !run->ok;
        e.lost += run->lost;
        ate.push_back(run->ate_rmse);
        ate_sd.push_back(run->ate_std);
        rt.push_back(run->rpe_trans_rmse);
        rt_sd.push_back(run->rpe_trans_std);
        rr.push_back(run->rpe_rot_rmse);
        rr_sd.push_back(run->rpe_rot_std);
        p.push_back(run->precision);
        pb.push_back(run->precision_without_boundary);
        r.push_back(run->recall);
        pd.push_back(run->precision_with_depth);
        rd.push_back(run->recall_with_depth);
        tracked.push_back(run->frames ? static_cast<double>(run->tracked) / run->frames : NAN);
        moving.push_back(run->moving_share);
        posed.push_back(run->frames ? static_cast<double>(run->posed) / run->frames : NAN);
        maps.push_back(run->maps);
        ate_all.push_back(run->ate_all_maps_rmse);
      }
      e.ate_rmse = mean_std(ate);
      e.ate_std = mean_std(ate_sd);
      e.rpe_trans_rmse = mean_std(rt);
      e.rpe_trans_std = mean_std(rt_sd);
      e.rpe_rot_rmse = mean_std(rr);
      e.rpe_rot_std = mean_std(rr_sd);
      e.precision = mean_std(p);
      e.precision_without_boundary = mean_std(pb);
      e.recall = mean_std(r);
      e.precision_with_depth = mean_std(pd);
      e.recall_with_depth = mean_std(rd);
      e.tracked_share = mean_std(tracked);
      e.moving_share = mean_std(moving);
      e.posed_share = mean_std(posed);
      e.maps = mean_std(maps);
      e.ate_all_maps_rmse = mean_std(ate_all);
      summary.entries.push_back(e);
    }
  return summary;
}

SweepSummary summarize_sweep(const SweepPlan& plan, const SweepLayout& layout) {
  std::vector<RunRecord> records;
  std::vector<std::pair<const SweepJob*, RecordState>> unfinished;  // failed or corrupt
  std::vector<std::string> corrupt;
  for (const auto& job : plan.jobs) {
    if (job.kind != JobKind::kSlam) continue;
    JobRecordState s = job_record_state(layout, job);
    if (s.state == RecordState::kDone) records.push_back(std::move(*s.run));
    if (s.state == RecordState::kFailed || s.state == RecordState::kCorrupt)
      unfinished.emplace_back(&job, s.state);
    if (s.state == RecordState::kCorrupt) corrupt.push_back(s.problem);
  }
  SweepSummary summary = summarize_records(plan, records);
  summary.corrupt = corrupt;
  for (const auto& [job, state] : unfinished) {
    summary.failed_jobs += state == RecordState::kFailed;
    for (auto& e : summary.entries)
      if (e.mode == job->mode &&
          std::find(job->cells.begin(), job->cells.end(), e.cell) != job->cells.end())
        (state == RecordState::kFailed ? e.failed_jobs : e.corrupt)++;
  }
  return summary;
}

}  // namespace depot::harness
