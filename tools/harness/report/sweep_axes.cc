#include "tools/harness/report/sweep_axes.h"

#include <algorithm>
#include <cstdlib>
#include <map>

namespace depot::harness {
namespace {

// A level's position on a numeric axis (text levels keep their order).
double level_order(const std::string& level) {
  char* end = nullptr;
  const double v = std::strtod(level.c_str(), &end);
  return end != level.c_str() && *end == '\0' ? v : 0.0;
}

}  // namespace

std::vector<SweepAxis> sweep_axes(const SweepPlan& plan, size_t k) {
  // Cells that differ only in parameter k, keyed by everything else.
  std::map<std::string, std::vector<size_t>> groups;
  for (size_t c = 0; c < plan.cells.size(); ++c) {
    const SweepCell& cell = plan.cells[c];
    std::string key = plan.spec.scenarios[cell.scenario].name;
    for (size_t j = 0; j < cell.levels.size(); ++j)
      if (j != k) key += " " + plan.spec.vary[j].name + "=" + cell.levels[j];
    groups[key].push_back(c);
  }
  std::vector<SweepAxis> axes;
  for (auto& [group, cells] : groups) {
    // Numeric levels in increasing order, so lines do not zigzag.
    std::stable_sort(cells.begin(), cells.end(), [&](size_t a, size_t b) {
      return level_order(plan.cells[a].levels[k]) < level_order(plan.cells[b].levels[k]);
    });
    SweepAxis axis{k, group, cells, {}};
    for (size_t c : cells) axis.levels.push_back(plan.cells[c].levels[k]);
    axes.push_back(axis);
  }
  return axes;
}

}  // namespace depot::harness
