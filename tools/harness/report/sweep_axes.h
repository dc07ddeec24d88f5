#pragma once
// A sweep read along one varied parameter: the cells that differ only in it,
// in increasing order of its level (text levels keep the order written).
// Shared by the plots and the breaking points.
#include <string>
#include <vector>

#include "tools/harness/plan/sweep_plan.h"

namespace depot::harness {

struct SweepAxis {
  size_t parameter = 0;       // index into spec.vary
  std::string group;          // the other parameters' levels, "scenario p=v ..."
  std::vector<size_t> cells;  // in level order
  std::vector<std::string> levels;
};

// Every axis along varied parameter k, one per combination of the others.
std::vector<SweepAxis> sweep_axes(const SweepPlan& plan, size_t k);

}  // namespace depot::harness
