#include "tools/harness/report/sweep_figures.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "eval/series_plot.h"
#include "tools/harness/report/breaking_points.h"
#include "tools/harness/report/sweep_tables.h"

namespace depot::harness {
namespace {

// One colour per mode in every report: orb red, orb+yolo blue, orb+lk
// orange, full green, masked the fifth.
size_t mode_colour_index(const std::string& mode) {
  static const char* modes[] = {"orb", "orb+yolo", "orb+lk", "full", "masked"};
  for (size_t i = 0; i < 5; ++i)
    if (mode == modes[i]) return i;
  return 5;
}

// `group_index` names the file when several figures share a parameter.
// `breaks`: where each mode (spec order) first breaks the bounds along this
// axis, ringed on the ATE and tracked plots with their bounds drawn; empty
// for plots that are not along a numeric parameter.
void add_pair(const SweepPlan& plan, const SweepSummary& s, const std::vector<size_t>& cells,
              const std::vector<std::string>& levels, const std::string& x_label,
              const std::string& group, const std::string& group_index, const std::string& stem,
              const std::vector<BreakingPoint>& breaks, std::vector<Figure>& out) {
  eval::SeriesPlot ate;
  ate.title = "ATE RMSE vs " + x_label + (group.empty() ? "" : " (" + group + ")");
  ate.x_label = x_label;
  ate.y_label = "ATE RMSE (m)";
  ate.x_levels = levels;
  ate.log_y = true;
  eval::SeriesPlot rejection = ate;
  rejection.title =
      "Rejection precision / recall vs " + x_label + (group.empty() ? "" : " (" + group + ")");
  rejection.y_label =
      "precision, boundary points left out (solid, circles), recall (dashed, squares)";
  rejection.log_y = false;
  rejection.y_lo = 0.0;
  rejection.y_hi = 1.0;
  // Rejection may cost frames: ATE alone, over the frames kept, hides that.
  eval::SeriesPlot tracked = ate;
  tracked.title = "Tracked share vs " + x_label + (group.empty() ? "" : " (" + group + ")");
  tracked.y_label = "frames with a pose / frames";
  tracked.log_y = false;
  tracked.y_lo = 0.0;
  tracked.y_hi = 1.0;
  if (!breaks.empty()) {
    ate.thresholds.push_back({kBreakingAte, "5 cm"});
    tracked.thresholds.push_back({kBreakingTracked, "90 %"});
  }
  bool any_ate = false, any_rejection = false;
  for (size_t m = 0; m < plan.spec.modes.size(); ++m) {
    const std::string& mode = plan.spec.modes[m];
    const std::string colour = eval::series_colour(mode_colour_index(mode));
    eval::PlotSeries a{mode, colour, "", {}, {}};
    eval::PlotSeries t{mode, colour, "", {}, {}};
    eval::PlotSeries p{mode + " precision", colour, "", {}, {}};
    eval::PlotSeries r{mode + " recall", colour, "6 4", {}, {}, eval::PlotMarker::kSquare};
    for (size_t c : cells) {
      const CellModeSummary& e = *s.find(c, mode);
      a.mean.push_back(e.ate_rmse.mean);
      a.std.push_back(e.ate_rmse.std);
      t.mean.push_back(e.tracked_share.mean);
      t.std.push_back(e.tracked_share.std);
      p.mean.push_back(e.precision_without_boundary.mean);
      p.std.push_back(e.precision_without_boundary.std);
      r.mean.push_back(e.recall.mean);
      r.std.push_back(e.recall.std);
      any_ate = any_ate || e.ate_rmse.count > 0;
      any_rejection = any_rejection || e.precision_without_boundary.count > 0 || e.recall.count > 0;
    }
    if (m < breaks.size() && breaks[m].ate >= 0)
      ate.rings.push_back(
          {ate.series.size(), static_cast<size_t>(breaks[m].ate), mode + " > 5 cm"});
    if (m < breaks.size() && breaks[m].tracked >= 0)
      tracked.rings.push_back(
          {tracked.series.size(), static_cast<size_t>(breaks[m].tracked), mode + " < 90 %"});
    ate.series.push_back(a);
    tracked.series.push_back(t);
    if (mode != "orb") {
      rejection.series.push_back(p);
      rejection.series.push_back(r);
    }
  }
  const std::string suffix = group_index.empty() ? "" : "__" + group_index;
  if (any_ate) {
    out.push_back({"ate_vs_" + stem + suffix + ".svg", ate.title, render_series_plot_svg(ate)});
    out.push_back(
        {"tracked_vs_" + stem + suffix + ".svg", tracked.title, render_series_plot_svg(tracked)});
  }
  if (any_rejection)
    out.push_back({"rejection_vs_" + stem + suffix + ".svg", rejection.title,
                   render_series_plot_svg(rejection)});
}

}  // namespace

std::vector<Figure> sweep_figures(const SweepPlan& plan, const SweepSummary& s) {
  std::vector<Figure> out;
  if (plan.spec.vary.empty()) {
    std::vector<size_t> cells;
    std::vector<std::string> names;
    for (size_t c = 0; c < plan.cells.size(); ++c) {
      cells.push_back(c);
      names.push_back(plan.spec.scenarios[plan.cells[c].scenario].name);
    }
    add_pair(plan, s, cells, names, "scenario", "", "", "scenario", {}, out);
    return out;
  }
  for (size_t k = 0; k < plan.spec.vary.size(); ++k) {
    const std::string& name = plan.spec.vary[k].name;
    const std::vector<SweepAxis> axes = sweep_axes(plan, k);
    size_t index = 0;
    for (const SweepAxis& axis : axes) {
      // Dynamic load is a knob; what it gives is the moving-pixel share,
      // measured on the datasets: each level shows both.
      std::vector<std::string> levels = axis.levels;
      if (name == "load") {
        const std::vector<double> shares = moving_shares(s, axis, plan.spec.modes);
        for (size_t i = 0; i < levels.size(); ++i)
          if (std::isfinite(shares[i])) levels[i] += fmt::format(" ({:.0f} %)", 100 * shares[i]);
      }
      const std::string x_label = name == "load" ? "load (moving-pixel share measured)" : name;
      const bool one_group = axes.size() == 1;
      add_pair(plan, s, axis.cells, levels, x_label, one_group ? "" : axis.group,
               one_group ? "" : std::to_string(++index), file_safe(name),
               numeric_axis(axis) ? breaking_points(plan, s, axis) : std::vector<BreakingPoint>{},
               out);
    }
  }
  return out;
}

std::vector<std::string> default_figure_runs(const SweepPlan& plan) {
  std::vector<std::string> modes;
  const std::string cmp = compared_mode(plan.spec);
  if (has_mode(plan.spec, "orb") && !cmp.empty())
    modes = {"orb", cmp};
  else
    modes = plan.spec.modes;
  std::vector<std::string> ids;
  const size_t last = plan.cells.size() - 1;
  for (const auto& mode : modes)
    for (const auto& job : plan.jobs)
      if (job.kind == JobKind::kSlam && job.seed == 1 && job.mode == mode &&
          std::find(job.cells.begin(), job.cells.end(), last) != job.cells.end())
        ids.push_back(job.id);
  return ids;
}

}  // namespace depot::harness
