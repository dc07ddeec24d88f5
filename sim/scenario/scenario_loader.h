#pragma once
#include <string>

#include "sim/scenario/scenario.h"

namespace depot::sim {

// Reads and validates a scenario; every problem throws depot::Error
// "<file>:<line>: <problem>". Relative paths resolve against the YAML's folder.
Scenario load_scenario(const std::string& path);

// Scales number, size and speed of the living actors by one load factor
// (0 = no living actors, 1 = as written, up to 4). Deterministic.
void apply_dynamic_load(Scenario& scenario, double load);

// The names of the scenarios shipped in `folder` (sorted).
std::vector<std::string> list_scenarios(const std::string& folder);

}  // namespace depot::sim
