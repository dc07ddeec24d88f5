#pragma once
// Where each mode breaks as a varied parameter rises (the stress sweeps'
// question, e.g. dynamic load): the first level whose mean over seeds has
// an ATE RMSE above 5 cm, and the first whose mean tracked share is below
// 90 %, each with the moving-pixel share measured on its datasets.
#include <string>
#include <vector>

#include "tools/harness/report/result_table.h"
#include "tools/harness/report/sweep_axes.h"
#include "tools/harness/report/sweep_summary.h"

namespace depot::harness {

constexpr double kBreakingAte = 0.05;     // m
constexpr double kBreakingTracked = 0.9;  // share of frames

// -1 = the mode holds at every level of the axis.
struct BreakingPoint {
  std::string mode;
  int ate = -1;      // index into the axis's levels
  int tracked = -1;  // index into the axis's levels
};

// Whether every level of the axis is a number (and there are two or more):
// only such axes have breaking points.
bool numeric_axis(const SweepAxis& axis);

// One per mode of the sweep along `axis`; a level where the mode has no
// finished run does not count, one where none of its runs kept a trajectory
// breaks both bounds.
std::vector<BreakingPoint> breaking_points(const SweepPlan& plan, const SweepSummary& summary,
                                           const SweepAxis& axis);

// The moving-pixel share measured at each level of the axis (mean over the
// datasets of its cell; NaN where none was rendered yet).
std::vector<double> moving_shares(const SweepSummary& summary, const SweepAxis& axis,
                                  const std::vector<std::string>& modes);

// "Breaking points": one row per axis and mode along every numeric varied
// parameter; empty when nothing is varied.
Table breaking_point_table(const SweepPlan& plan, const SweepSummary& summary);

}  // namespace depot::harness
