#pragma once
// What a sweep varies and runs, as plain data: scenarios, the parameters and
// their levels, fixed settings, modes, seeds and run size. Stored in the
// sweep folder (sweep.json) so a killed sweep resumes with exactly the same
// plan, and so a cluster job can run one of its jobs by id.
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/yaml_overrides.h"

namespace depot::harness {

// Where a parameter acts: a key of the scenario file (rendering), of the
// simulated detector's configuration, which detector runs (sim or a real
// network, `detector`), or of the rejection's extensions (SLAM).
enum class ParameterTarget { kScenario, kDetector, kDetectorChoice, kRejection };

// A parameter name as the user writes it, resolved. Accepted names:
//   scenario.<key path>   any scenario key, e.g. scenario.sensor.rgb_noise
//   detector.<key>        any simulated-detector key, e.g. detector.jitter
//   rejection.<key>       our extensions of full: background_margin, ego_flow,
//                         test_static
//   load                  = scenario.dynamic_load (number, size, speed of actors)
//   miss_rate, latency    = detector.miss_rate, detector.latency_frames
//   detector              which detector: sim, darknet, xl, fastestdet, yolov5
//                         (as `slam run --detector`; detector.KEY needs sim)
//   depth_noise, rgb_noise = scenario.sensor.disparity_noise / rgb_noise
struct ParameterKey {
  std::string name;  // as written
  ParameterTarget target = ParameterTarget::kScenario;
  std::string key;  // key inside its target
};
// Throws Error("<where>: unknown parameter ...") for any other name.
ParameterKey resolve_parameter(const std::string& name, const std::string& where = "--vary");

struct SweepParameter {
  std::string name;                 // as written ("load")
  std::vector<std::string> values;  // levels, as written ("0", "0.5", ...)
};

// "load=0,0.5,1" -> {load, [0, 0.5, 1]}. Throws Error naming `where`.
SweepParameter parse_sweep_parameter(const std::string& text, const std::string& where);

struct SweepScenario {
  std::string name;  // the scenario's name, used in ids and tables
  std::string path;  // resolved YAML file
};

struct SweepSpec {
  std::vector<SweepScenario> scenarios;
  std::vector<SweepParameter> vary;   // the grid is their product
  std::vector<SweepParameter> fixed;  // one value each, applied to every run
  std::vector<std::string> modes = {"orb", "orb+yolo", "orb+lk", "full"};
  int seeds = 3;
  int frames = 300;
  int width = 640;
  bool sync_mapping = true;  // reproducible runs (mapping in the tracking thread)
  bool keep_data = false;    // keep rendered datasets after their runs finish
  // Each "system:NAME" mode's system file, absolute (as scenario paths are),
  // so the sweep's `status`, `resume` and jobs find it from any folder.
  std::map<std::string, std::string> systems;
};

// Fills `systems` for every system mode not in it yet: the file the name
// stands for (tools/system/system_spec.h), made absolute. Throws Error when
// there is no such file.
void resolve_system_files(SweepSpec& spec);

// The system file of a "system:NAME" mode of the sweep.
std::string system_file(const SweepSpec& spec, const std::string& mode);

// Checks names, levels, modes and ranges; throws Error("<where>: ...").
void validate(const SweepSpec& spec, const std::string& where);

nlohmann::json to_json(const SweepSpec& spec);
// Throws Error("<where>: ...") on a missing or mistyped field.
SweepSpec sweep_spec_from_json(const nlohmann::json& json, const std::string& where);

}  // namespace depot::harness
