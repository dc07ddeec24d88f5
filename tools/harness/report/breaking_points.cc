#include "tools/harness/report/breaking_points.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>

namespace depot::harness {
namespace {

bool numeric(const std::string& level) {
  char* end = nullptr;
  std::strtod(level.c_str(), &end);
  return end != level.c_str() && *end == '\0';
}

// "1.5 (share 23.4 %)", or "holds up to 4 (share 41.0 %)".
std::string where(const SweepAxis& axis, const std::vector<double>& shares, int index) {
  const bool holds = index < 0;
  const size_t i = holds ? axis.levels.size() - 1 : static_cast<size_t>(index);
  const std::string share =
      std::isfinite(shares[i]) ? fmt::format(" (moving {:.1f} %)", 100 * shares[i]) : "";
  return (holds ? "holds to " : "") + axis.levels[i] + share;
}

}  // namespace

bool numeric_axis(const SweepAxis& axis) {
  bool all = axis.levels.size() >= 2;
  for (const auto& level : axis.levels) all = all && numeric(level);
  return all;
}

std::vector<BreakingPoint> breaking_points(const SweepPlan& plan, const SweepSummary& summary,
                                           const SweepAxis& axis) {
  std::vector<BreakingPoint> out;
  for (const std::string& mode : plan.spec.modes) {
    BreakingPoint b{mode};
    for (size_t i = 0; i < axis.cells.size(); ++i) {
      const CellModeSummary* e = summary.find(axis.cells[i], mode);
      if (!e) continue;
      // No seed keeping a trajectory at all is past breaking too.
      const bool none_kept = e->runs > 0 && e->without_trajectory == e->runs;
      if (b.ate < 0 && ((e->ate_rmse.count > 0 && e->ate_rmse.mean > kBreakingAte) || none_kept))
        b.ate = static_cast<int>(i);
      // A run without a trajectory tracked nothing: its share counts as 0.
      if (b.tracked < 0 && e->runs > 0 && e->tracked_share.mean < kBreakingTracked)
        b.tracked = static_cast<int>(i);
    }
    out.push_back(b);
  }
  return out;
}

std::vector<double> moving_shares(const SweepSummary& summary, const SweepAxis& axis,
                                  const std::vector<std::string>& modes) {
  std::vector<double> shares;
  for (size_t c : axis.cells) {
    double share = NAN;
    for (const std::string& mode : modes) {
      const CellModeSummary* e = summary.find(c, mode);
      if (e && e->moving_share.count > 0) {
        share = e->moving_share.mean;
        break;
      }
    }
    shares.push_back(share);
  }
  return shares;
}

Table breaking_point_table(const SweepPlan& plan, const SweepSummary& summary) {
  Table t;
  t.title = "Breaking points";
  t.caption = fmt::format(
      "Along each numeric varied parameter, the first level at which a mode's mean over seeds "
      "has an ATE RMSE above {:.0f} cm, and the first at which its mean tracked share falls "
      "below {:.0f} % (\"holds to\": not within the levels swept), with the moving-pixel share "
      "measured on that level's datasets; a level where no seed kept a trajectory counts as "
      "past both. The plots ring the same points.",
      100 * kBreakingAte, 100 * kBreakingTracked);
  t.columns = {{"axis"}, {"parameter"}, {"mode"}, {"ATE > 5 cm from"}, {"tracked < 90 % from"}};
  for (size_t k = 0; k < plan.spec.vary.size(); ++k) {
    for (const SweepAxis& axis : sweep_axes(plan, k)) {
      if (!numeric_axis(axis)) continue;
      const std::vector<double> shares = moving_shares(summary, axis, plan.spec.modes);
      for (const BreakingPoint& b : breaking_points(plan, summary, axis))
        t.rows.push_back({{axis.group, NAN, NAN},
                          {plan.spec.vary[k].name, NAN, NAN},
                          {b.mode, NAN, NAN},
                          {where(axis, shares, b.ate), NAN, NAN},
                          {where(axis, shares, b.tracked), NAN, NAN}});
    }
  }
  return t;
}

}  // namespace depot::harness
