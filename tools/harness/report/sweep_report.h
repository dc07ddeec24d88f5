#pragma once
// A sweep's report from whatever records exist (a partial sweep reports what
// has finished): report/tables.md, one CSV per table, the SVG plots, and one
// self-contained report.html with everything embedded (no external files,
// scripts or fonts), to open in any browser.
#include <string>
#include <vector>

#include "tools/harness/plan/sweep_plan.h"

namespace depot::harness {

struct ReportFiles {
  std::string html;               // report/report.html
  std::string markdown;           // report/tables.md
  std::string ablation_markdown;  // the Table 2 block, for the terminal
  size_t runs_found = 0, runs_expected = 0;
  std::vector<std::string> corrupt;  // records left out: "<path>: <problem>"
};

// `figure_runs`: run ids whose trajectory figures to embed (empty = default);
// an id that is not a run of the plan throws Error("--figures: ...").
ReportFiles write_sweep_report(const SweepPlan& plan, const SweepLayout& layout,
                               const std::vector<std::string>& figure_runs = {});

}  // namespace depot::harness
