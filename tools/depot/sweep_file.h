#pragma once
// A sweep written down (`depot sweep run --file F.yaml`): the command line's
// fields as YAML, for the sweeps shipped with the project (scenarios/stress/)
// or kept beside an experiment. Options given on the command line override
// the file's.
//
//   scenarios: [depot_walking_xyz, my_hall.yaml]   # names, or files beside this one
//   vary: {load: [0, 1, 2]}                         # each a list of levels
//   set: {scenario.sensor.rgb_noise: 3}             # one value each
//   modes: [orb, full, masked]
//   seeds: 3
//   frames: 300
//   width: 640
//   mapping: sync
#include <optional>
#include <string>
#include <vector>

namespace depot::cli {

struct SweepFile {
  std::vector<std::string> scenarios;    // shipped names or resolved paths
  std::vector<std::string> vary, fixed;  // "PARAM=L1,L2,..." as --vary and --set take them
  std::optional<std::vector<std::string>> modes;
  std::optional<int> seeds, frames, width;
  std::optional<std::string> mapping;
  std::string description;
};

// Throws depot::Error "<file>:<line>: <problem>" (unknown keys, wrong types,
// values out of the command line's ranges).
SweepFile read_sweep_file(const std::string& path);

}  // namespace depot::cli
