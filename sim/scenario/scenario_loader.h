#pragma once
#include <string>

#include "common/yaml_overrides.h"
#include "sim/scenario/scenario.h"

namespace depot::sim {

// Reads and validates a scenario; every problem throws depot::Error
// "<file>:<line>: <problem>". Relative paths resolve against the YAML's folder.
// `overrides` change keys of the file before it is read ("sensor.rgb_noise",
// "dynamic_load"), and are validated like the file's own keys.
Scenario load_scenario(const std::string& path, const std::vector<YamlOverride>& overrides = {});

// Scales number, size and speed of the living actors by one load factor
// (0 = no living actors, 1 = as written, up to 4). Deterministic.
void apply_dynamic_load(Scenario& scenario, double load);

// Sets the seed. A procedural hall drawn by it (no `seed_world`) is drawn
// again, and the motion's and actors' routes follow the new hall.
void set_scenario_seed(Scenario& scenario, uint64_t seed);

// The names of the scenarios shipped in `folder` (sorted).
std::vector<std::string> list_scenarios(const std::string& folder);

}  // namespace depot::sim
