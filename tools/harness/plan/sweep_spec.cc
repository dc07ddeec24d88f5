#include "tools/harness/plan/sweep_spec.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <utility>

#include "common/error.h"
#include "common/image_size.h"
#include "tools/system/system_spec.h"

namespace fs = std::filesystem;

namespace depot::harness {
namespace {

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0 && s.size() > prefix.size();
}

nlohmann::json parameter_json(const SweepParameter& p) {
  return {{"name", p.name}, {"values", p.values}};
}

std::vector<SweepParameter> parameters_from_json(const nlohmann::json& j) {
  std::vector<SweepParameter> out;
  for (const auto& p : j)
    out.push_back(
        {p.at("name").get<std::string>(), p.at("values").get<std::vector<std::string>>()});
  return out;
}

// The named parameters whose levels are plain numbers.
bool is_numeric_alias(const std::string& name) {
  return name == "load" || name == "depth_noise" || name == "rgb_noise" || name == "exposure" ||
         name == "readout" || name == "distortion" || name == "light" || name == "miss_rate" ||
         name == "latency";
}

}  // namespace

ParameterKey resolve_parameter(const std::string& name, const std::string& where) {
  struct Alias {
    const char* name;
    ParameterTarget target;
    const char* key;
  };
  static const Alias aliases[] = {
      {"load", ParameterTarget::kScenario, "dynamic_load"},
      {"depth_noise", ParameterTarget::kScenario, "sensor.disparity_noise"},
      {"rgb_noise", ParameterTarget::kScenario, "sensor.rgb_noise"},
      {"exposure", ParameterTarget::kScenario, "sensor.exposure"},
      {"readout", ParameterTarget::kScenario, "sensor.readout"},
      {"distortion", ParameterTarget::kScenario, "sensor.k1"},
      {"light", ParameterTarget::kScenario, "sensor.light"},
      {"miss_rate", ParameterTarget::kDetector, "miss_rate"},
      {"latency", ParameterTarget::kDetector, "latency_frames"},
      {"detector", ParameterTarget::kDetectorChoice, "type"},
  };
  for (const auto& a : aliases)
    if (name == a.name) return {name, a.target, a.key};
  if (starts_with(name, "scenario.")) return {name, ParameterTarget::kScenario, name.substr(9)};
  if (starts_with(name, "detector.")) return {name, ParameterTarget::kDetector, name.substr(9)};
  if (starts_with(name, "rejection.")) return {name, ParameterTarget::kRejection, name.substr(10)};
  fail(where,
       "unknown parameter '" + name +
           "' (use load, depth_noise, rgb_noise, exposure, readout, distortion, light, miss_rate, "
           "latency, detector, scenario.KEY, detector.KEY or rejection.KEY)");
}

SweepParameter parse_sweep_parameter(const std::string& text, const std::string& where) {
  const YamlOverride o = parse_yaml_override(text, where);
  SweepParameter p{o.key, {}};
  resolve_parameter(p.name, where);
  size_t start = 0;
  while (true) {
    const size_t comma = o.value.find(',', start);
    std::string v = o.value.substr(start, comma == std::string::npos ? comma : comma - start);
    v.erase(0, v.find_first_not_of(' '));
    v.erase(v.find_last_not_of(' ') + 1);
    if (v.empty()) fail(where, "empty level in '" + text + "'");
    if (is_numeric_alias(p.name)) {
      char* end = nullptr;
      const double number = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !std::isfinite(number))
        fail(where + " " + p.name, "level '" + v + "' is not a number");
    }
    p.values.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return p;
}

void validate(const SweepSpec& spec, const std::string& where) {
  if (spec.scenarios.empty()) fail(where, "no scenario");
  if (spec.modes.empty()) fail(where, "no mode");
  static const std::set<std::string> known = {"orb", "orb+yolo", "orb+lk", "full", "masked"};
  std::set<std::string> seen;
  for (const auto& m : spec.modes) {
    if (system::is_system_mode(m)) {
      // Another program: its file must load now, not when its first job runs.
      system::load_system_spec(system_file(spec, m));
    } else if (!known.count(m)) {
      fail(where, "unknown mode '" + m +
                      "' (expected orb, orb+yolo, orb+lk, full, masked, or system:NAME)");
    }
    if (!seen.insert(m).second) fail(where, "mode '" + m + "' given twice");
  }
  std::set<std::string> names;
  for (const auto& s : spec.scenarios)
    if (!names.insert(s.name).second) fail(where, "scenario '" + s.name + "' given twice");
  // Two names may reach one setting (load = scenario.dynamic_load), and a
  // key may contain another (scenario.sensor and scenario.sensor.rgb_noise):
  // either would silently overwrite a level.
  std::vector<std::pair<std::string, std::string>> keys;  // "target:key" -> name
  for (const auto* list : {&spec.vary, &spec.fixed})
    for (const auto& p : *list) {
      const ParameterKey k = resolve_parameter(p.name, where);
      const std::string full = std::to_string(static_cast<int>(k.target)) + ":" + k.key;
      for (const auto& [other, other_name] : keys)
        if (other == full || other.rfind(full + ".", 0) == 0 || full.rfind(other + ".", 0) == 0)
          fail(where, "parameters '" + other_name + "' and '" + p.name + "' set the same thing");
      keys.emplace_back(full, p.name);
      if (p.values.empty()) fail(where, "parameter '" + p.name + "' has no level");
      std::set<std::string> levels(p.values.begin(), p.values.end());
      if (levels.size() != p.values.size())
        fail(where, "parameter '" + p.name + "' repeats a level");
    }
  for (const auto& p : spec.fixed)
    if (p.values.size() != 1) fail(where, "fixed setting '" + p.name + "' needs one value");
  if (spec.seeds < 1 || spec.seeds > 1000) fail(where, "seeds must be in 1..1000");
  if (spec.frames < 10) fail(where, "frames must be at least 10");
  if (spec.width < kMinImageSide || spec.width > kMaxImageSide)
    fail(where, "width must be in " + std::to_string(kMinImageSide) + ".." +
                    std::to_string(kMaxImageSide));
}

nlohmann::json to_json(const SweepSpec& spec) {
  nlohmann::json scenarios = nlohmann::json::array();
  for (const auto& s : spec.scenarios) scenarios.push_back({{"name", s.name}, {"path", s.path}});
  nlohmann::json vary = nlohmann::json::array(), fixed = nlohmann::json::array();
  for (const auto& p : spec.vary) vary.push_back(parameter_json(p));
  for (const auto& p : spec.fixed) fixed.push_back(parameter_json(p));
  return {{"scenarios", scenarios},
          {"vary", vary},
          {"fixed", fixed},
          {"modes", spec.modes},
          {"seeds", spec.seeds},
          {"frames", spec.frames},
          {"width", spec.width},
          {"sync_mapping", spec.sync_mapping},
          {"keep_data", spec.keep_data},
          {"systems", spec.systems}};
}

void resolve_system_files(SweepSpec& spec) {
  for (const auto& m : spec.modes)
    if (system::is_system_mode(m) && !spec.systems.count(m))
      spec.systems[m] = fs::absolute(system::find_system_file(system::system_of_mode(m)))
                            .lexically_normal()
                            .string();
}

std::string system_file(const SweepSpec& spec, const std::string& mode) {
  auto it = spec.systems.find(mode);
  return system::find_system_file(it != spec.systems.end() ? it->second
                                                           : system::system_of_mode(mode));
}

SweepSpec sweep_spec_from_json(const nlohmann::json& j, const std::string& where) {
  SweepSpec spec;
  try {
    for (const auto& s : j.at("scenarios"))
      spec.scenarios.push_back({s.at("name").get<std::string>(), s.at("path").get<std::string>()});
    spec.vary = parameters_from_json(j.at("vary"));
    spec.fixed = parameters_from_json(j.at("fixed"));
    spec.modes = j.at("modes").get<std::vector<std::string>>();
    spec.seeds = j.at("seeds").get<int>();
    spec.frames = j.at("frames").get<int>();
    spec.width = j.at("width").get<int>();
    spec.sync_mapping = j.at("sync_mapping").get<bool>();
    spec.keep_data = j.at("keep_data").get<bool>();
    // Sweeps from before systems were stored: the names as they resolve here.
    if (j.contains("systems"))
      spec.systems = j.at("systems").get<std::map<std::string, std::string>>();
  } catch (const nlohmann::json::exception& e) {
    fail(where, std::string("not a sweep description: ") + e.what());
  }
  if (!j.contains("systems")) resolve_system_files(spec);
  validate(spec, where);
  return spec;
}

}  // namespace depot::harness
