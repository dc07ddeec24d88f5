#pragma once
// The sweep's plots: ATE RMSE against each varied parameter, one line per
// mode (log scale, error bars = std over seeds), and rejection precision and
// recall against it. With several parameters, one figure per combination of
// the others; without any, the x axis lists the scenarios.
#include <string>
#include <vector>

#include "tools/harness/report/sweep_summary.h"

namespace depot::harness {

struct Figure {
  std::string file;  // e.g. "ate_vs_load.svg"
  std::string title;
  std::string svg;
};

std::vector<Figure> sweep_figures(const SweepPlan& plan, const SweepSummary& summary);

// Runs whose trajectory figure (runs/<id>/ate.svg, like the paper's Figs. 6-7)
// the report shows by default: seed 1 of the last cell (the heaviest level),
// in orb and the compared mode, or every mode when orb is not run.
std::vector<std::string> default_figure_runs(const SweepPlan& plan);

}  // namespace depot::harness
