#pragma once
// The paper's tables for a sweep, one row per cell (scenario and levels):
//   ablation: ATE RMSE per mode, mean ± std over seeds, and Eq. 9 of full
//             against orb (paper Table 2);
//   ATE and RPE against orb: RMSE and S.D. of orb and of the compared mode
//             (full, else the last rejection mode) with Eq. 9 for each
//             (paper Tables 3 and 4);
//   rejection: precision and recall against the simulator's labels, tracked
//             share and lost frames per rejection mode;
//   frames:   every mode scored so that dropping frames cannot look good:
//             ATE over the trajectory, the tracked share, and ATE over the
//             frames of every atlas map (each aligned on its own) with the
//             share of frames that have a pose in any map.
#include <vector>

#include "tools/harness/report/result_table.h"
#include "tools/harness/report/sweep_summary.h"

namespace depot::harness {

Table ablation_table(const SweepPlan& plan, const SweepSummary& summary);
// Both empty (no rows) when the sweep lacks orb or a rejection mode.
Table ate_against_orb_table(const SweepPlan& plan, const SweepSummary& summary);
Table rpe_against_orb_table(const SweepPlan& plan, const SweepSummary& summary);
Table rejection_table(const SweepPlan& plan, const SweepSummary& summary);
Table frames_table(const SweepPlan& plan, const SweepSummary& summary);
// Every run: its levels, seed, mode and figures.
Table runs_table(const SweepPlan& plan, const SweepSummary& summary);

bool has_mode(const SweepSpec& spec, const std::string& mode);

// The mode compared against orb: "full" if run, else the last non-orb mode,
// else "".
std::string compared_mode(const SweepSpec& spec);

}  // namespace depot::harness
