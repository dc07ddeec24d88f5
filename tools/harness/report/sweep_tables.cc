#include "tools/harness/report/sweep_tables.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "eval/improvement.h"

namespace depot::harness {
namespace {

TableValue text(const std::string& s) {
  return {s, NAN, NAN};
}
TableValue number(double mean, double std = NAN) {
  return {"", mean, std};
}
// One seed has no spread to show.
TableValue number(const MeanStd& m) {
  return {"", m.mean, m.count > 1 ? m.std : NAN};
}

// Scenario and one column per varied parameter.
void add_cell_columns(const SweepPlan& plan, Table& t) {
  t.columns.push_back({"scenario"});
  for (const auto& p : plan.spec.vary) t.columns.push_back({p.name});
}

std::vector<TableValue> cell_values(const SweepPlan& plan, size_t cell) {
  std::vector<TableValue> row{text(plan.spec.scenarios[plan.cells[cell].scenario].name)};
  for (const auto& level : plan.cells[cell].levels) row.push_back(text(level));
  return row;
}

MeanStd moving_share(const SweepPlan& plan, const SweepSummary& s, size_t cell) {
  for (const auto& mode : plan.spec.modes) {
    const CellModeSummary* e = s.find(cell, mode);
    if (e && e->moving_share.count) return e->moving_share;
  }
  return {};
}

std::string runs_text(const SweepPlan& plan, const SweepSummary& s, size_t cell) {
  // The words of `depot sweep status` (sweep_job_state.h).
  int runs = 0, no_trajectory = 0, failed = 0, corrupt = 0;
  for (const auto& mode : plan.spec.modes)
    if (const CellModeSummary* e = s.find(cell, mode)) {
      runs += e->runs;
      no_trajectory += e->without_trajectory;
      failed += e->failed_jobs;
      corrupt += e->corrupt;
    }
  std::string t = std::to_string(runs) + " of " +
                  std::to_string(plan.spec.seeds * static_cast<int>(plan.spec.modes.size()));
  std::string notes;
  for (const auto& [n, what] : {std::pair<int, const char*>{no_trajectory, "without a trajectory"},
                                {failed, "failed"},
                                {corrupt, "corrupt"}})
    if (n) notes += (notes.empty() ? "" : ", ") + std::to_string(n) + " " + what;
  return notes.empty() ? t : t + " (" + notes + ")";
}

// The RPE delta the runs used (all runs of a sweep use the same).
std::string rpe_delta_text(const SweepSummary& s) {
  return fmt::format("{:g} s", s.runs.empty() ? 1.0 : s.runs.front().rpe_delta_s);
}

}  // namespace

bool has_mode(const SweepSpec& spec, const std::string& mode) {
  return std::find(spec.modes.begin(), spec.modes.end(), mode) != spec.modes.end();
}

std::string compared_mode(const SweepSpec& spec) {
  if (has_mode(spec, "full")) return "full";
  for (auto it = spec.modes.rbegin(); it != spec.modes.rend(); ++it)
    if (*it != "orb") return *it;
  return "";
}

Table ablation_table(const SweepPlan& plan, const SweepSummary& s) {
  Table t;
  t.title = "Ablation: ATE RMSE per mode (paper Table 2)";
  t.caption =
      "ATE RMSE in m after SE(3) alignment, mean ± std over " + std::to_string(plan.spec.seeds) +
      " seed(s), " + std::to_string(plan.spec.frames) + " frames at " +
      std::to_string(plan.spec.width) +
      " px. Moving px = share of pixels on moving objects (measured). ATE covers the tracked "
      "frames only (lost frames have no pose, as in ORB-SLAM2): read it beside the tracked "
      "share (the tracked column of the rejection table); a run that loses tracking for good "
      "has a short trajectory. The paired difference is the compared mode's "
      "ATE minus orb's on the same seed (mm, mean ± std; negative = better than orb), and t "
      "its paired t statistic: |t| under about 2 means the seeds show no difference. With "
      "masked and full both run, masked - full is the same on those two modes.";
  add_cell_columns(plan, t);
  t.columns.push_back({"moving px", 1, false, " %"});
  for (const auto& mode : plan.spec.modes) t.columns.push_back({mode, 4, true});
  const std::string cmp = compared_mode(plan.spec);
  const bool eq9 = has_mode(plan.spec, "orb") && !cmp.empty();
  if (eq9) {
    t.columns.push_back({cmp + " vs orb (Eq. 9)", 1, false, " %"});
    t.columns.push_back({cmp + " - orb, paired (mm)", 2, true});
    t.columns.push_back({"t", 1});
  }
  // Our mode beyond boxes against the paper's full, paired by seed.
  const bool masked_vs_full = has_mode(plan.spec, "masked") && has_mode(plan.spec, "full");
  if (masked_vs_full) {
    t.columns.push_back({"masked - full, paired (mm)", 2, true});
    t.columns.push_back({"t (masked - full)", 1});
  }
  t.columns.push_back({"runs"});
  for (size_t c = 0; c < plan.cells.size(); ++c) {
    auto row = cell_values(plan, c);
    const MeanStd moving = moving_share(plan, s, c);
    row.push_back(number(100 * moving.mean));
    for (const auto& mode : plan.spec.modes) row.push_back(number(s.find(c, mode)->ate_rmse));
    if (eq9) {
      const CellModeSummary &orb = *s.find(c, "orb"), &ours = *s.find(c, cmp);
      row.push_back(number(paired_improvement(orb, ours, &RunRecord::ate_rmse)));
      const PairedDifference d = paired_difference(orb, ours, &RunRecord::ate_rmse);
      MeanStd mm = d.difference;  // m -> mm
      mm.mean *= 1000, mm.std *= 1000;
      row.push_back(number(mm));
      row.push_back(number(d.t));
    }
    if (masked_vs_full) {
      const PairedDifference d =
          paired_difference(*s.find(c, "full"), *s.find(c, "masked"), &RunRecord::ate_rmse);
      MeanStd mm = d.difference;
      mm.mean *= 1000, mm.std *= 1000;
      row.push_back(number(mm));
      row.push_back(number(d.t));
    }
    row.push_back(text(runs_text(plan, s, c)));
    t.rows.push_back(row);
  }
  return t;
}

namespace {

// One figure of Tables 3-4: orb's and the compared mode's value (means over
// seeds), and optionally Eq. 9 between them.
struct AgainstOrbMetric {
  std::string name;
  int decimals;
  MeanStd CellModeSummary::*field;
  double RunRecord::*figure;  // the same figure per run, for Eq. 9 on paired seeds
};

Table against_orb_table(const SweepPlan& plan, const SweepSummary& s, const std::string& title,
                        const std::string& caption, const std::vector<AgainstOrbMetric>& metrics) {
  Table t;
  const std::string cmp = compared_mode(plan.spec);
  t.title = title;
  t.caption = caption;
  if (!has_mode(plan.spec, "orb") || cmp.empty()) return t;
  add_cell_columns(plan, t);
  for (const auto& m : metrics) {
    t.columns.push_back({"orb " + m.name, m.decimals});
    t.columns.push_back({cmp + " " + m.name, m.decimals});
    t.columns.push_back({m.name + " improvement", 1, false, " %"});
  }
  for (size_t c = 0; c < plan.cells.size(); ++c) {
    const CellModeSummary& o = *s.find(c, "orb");
    const CellModeSummary& f = *s.find(c, cmp);
    auto row = cell_values(plan, c);
    for (const auto& m : metrics) {
      row.push_back(number((o.*m.field).mean));
      row.push_back(number((f.*m.field).mean));
      row.push_back(number(paired_improvement(o, f, m.figure)));
    }
    t.rows.push_back(row);
  }
  return t;
}

}  // namespace

Table ate_against_orb_table(const SweepPlan& plan, const SweepSummary& s) {
  return against_orb_table(
      plan, s, "ATE against orb (paper Table 3)",
      "RMSE and S.D. of the absolute trajectory error (m), each averaged over seeds; "
      "improvement by Eq. 9, rho = (orb - " +
          compared_mode(plan.spec) + ") / orb, on the seeds both modes finished.",
      {{"RMSE", 4, &CellModeSummary::ate_rmse, &RunRecord::ate_rmse},
       {"S.D.", 4, &CellModeSummary::ate_std, &RunRecord::ate_std}});
}

Table rpe_against_orb_table(const SweepPlan& plan, const SweepSummary& s) {
  return against_orb_table(
      plan, s, "RPE against orb (paper Table 4)",
      "Relative pose error over " + rpe_delta_text(s) +
          ": translation RMSE and S.D. (m) and rotation RMSE (deg), each averaged over seeds; "
          "improvement by Eq. 9 on the seeds both modes finished.",
      {{"trans RMSE", 4, &CellModeSummary::rpe_trans_rmse, &RunRecord::rpe_trans_rmse},
       {"trans S.D.", 4, &CellModeSummary::rpe_trans_std, &RunRecord::rpe_trans_std},
       {"rot RMSE", 3, &CellModeSummary::rpe_rot_rmse, &RunRecord::rpe_rot_rmse}});
}

Table rejection_table(const SweepPlan& plan, const SweepSummary& s) {
  Table t;
  t.title = "Rejection against ground truth";
  t.caption =
      "Keypoints rejected as dynamic vs keypoints on objects flagged moving by the "
      "simulator (precision, recall: mean ± std over seeds). Boundary points (centre on the "
      "background, FAST circle touching a mover) are left out of `precision` and counted as "
      "static in `precision (boundary static)`; recall is the same both ways. The with-depth "
      "columns score only the keypoints with a depth reading (boundary points left out): only "
      "they start map points (empty for another system's runs). tracked = share "
      "of the frames given that have a pose in the final trajectory (mean over seeds; lost "
      "frames and frames of a map abandoned by a reset have none); lost = frames tracking "
      "reported lost, summed over seeds.";
  add_cell_columns(plan, t);
  t.columns.push_back({"mode"});
  t.columns.push_back({"precision", 3, true});
  t.columns.push_back({"precision (boundary static)", 3, true});
  t.columns.push_back({"recall", 3, true});
  t.columns.push_back({"precision with depth", 3, true});
  t.columns.push_back({"recall with depth", 3, true});
  t.columns.push_back({"tracked", 1, false, " %"});
  t.columns.push_back({"lost frames", 0});
  t.columns.push_back({"runs without trajectory", 0});
  for (size_t c = 0; c < plan.cells.size(); ++c)
    for (const auto& mode : plan.spec.modes) {
      const CellModeSummary& e = *s.find(c, mode);
      auto row = cell_values(plan, c);
      row.push_back(text(mode));
      row.push_back(number(e.precision_without_boundary));
      row.push_back(number(e.precision));
      row.push_back(number(e.recall));
      row.push_back(number(e.precision_with_depth));
      row.push_back(number(e.recall_with_depth));
      row.push_back(number(100 * e.tracked_share.mean));
      row.push_back(number(e.runs ? e.lost : NAN));
      row.push_back(number(e.runs ? e.without_trajectory : NAN));
      t.rows.push_back(row);
    }
  return t;
}

Table frames_table(const SweepPlan& plan, const SweepSummary& s) {
  Table t;
  t.title = "Every frame counted";
  t.caption =
      "ATE over the trajectory (m) only sees the frames it holds; beside it the share of "
      "frames given that are in it (tracked), the share with a pose in any map of the atlas "
      "(posed: the trajectory's map and maps never merged into it), the maps holding frames, "
      "and ATE over all posed frames with each map aligned to the ground truth on its own "
      "(m). Means ± std over seeds.";
  add_cell_columns(plan, t);
  t.columns.push_back({"mode"});
  t.columns.push_back({"ATE RMSE", 4, true});
  t.columns.push_back({"tracked", 1, false, " %"});
  t.columns.push_back({"posed", 1, false, " %"});
  t.columns.push_back({"maps", 1, true});
  t.columns.push_back({"ATE all maps", 4, true});
  for (size_t c = 0; c < plan.cells.size(); ++c)
    for (const auto& mode : plan.spec.modes) {
      const CellModeSummary& e = *s.find(c, mode);
      auto row = cell_values(plan, c);
      row.push_back(text(mode));
      row.push_back(number(e.ate_rmse));
      row.push_back(number(100 * e.tracked_share.mean));
      row.push_back(number(100 * e.posed_share.mean));
      row.push_back(number(e.maps));
      row.push_back(number(e.ate_all_maps_rmse));
      t.rows.push_back(row);
    }
  return t;
}

Table runs_table(const SweepPlan& plan, const SweepSummary& s) {
  Table t;
  t.title = "All runs";
  t.caption =
      "One row per finished run; its folder runs/<id>/ holds trajectory.txt (the tracked "
      "frames), states.txt (every frame's state and map), atlas.txt (every frame with a pose, "
      "in its map's frame), stats.csv, ate.svg and result.json. tracked = frames in the "
      "trajectory / frames given; posed = frames with a pose in any map / frames given. "
      "precision leaves boundary points out; precision (b. static) counts them as static.";
  t.columns = {{"run"},
               {"seed"},
               {"mode"},
               {"ATE RMSE", 4},
               {"RPE trans RMSE", 4},
               {"precision", 3},
               {"precision (b. static)", 3},
               {"recall", 3},
               {"tracked", 1, false, " %"},
               {"posed", 1, false, " %"},
               {"ATE all maps", 4},
               {"seconds", 1},
               {"note"}};
  for (const auto& r : s.runs)
    t.rows.push_back({text(r.id), text(std::to_string(r.seed)), text(r.mode), number(r.ate_rmse),
                      number(r.rpe_trans_rmse), number(r.precision_without_boundary),
                      number(r.precision), number(r.recall),
                      number(r.frames ? 100.0 * r.tracked / r.frames : NAN),
                      number(r.frames ? 100.0 * r.posed / r.frames : NAN),
                      number(r.ate_all_maps_rmse), number(r.seconds), text(r.ok ? "" : r.error)});
  return t;
}

}  // namespace depot::harness
