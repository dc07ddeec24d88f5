#include "tools/system/system_spec.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "common/config_path.h"
#include "common/error.h"
#include "common/yaml_file.h"

namespace fs = std::filesystem;

namespace depot::system {
namespace {

// Calls visit(name, begin, end) for each placeholder "{name}" in `text`
// (name: lower-case letters and '_'); other braces, e.g. a shell or awk
// script's, are text.
template <typename Visit>
void for_each_placeholder(const std::string& text, Visit visit) {
  size_t at = 0;
  while ((at = text.find('{', at)) != std::string::npos) {
    size_t end = at + 1;
    while (end < text.size() &&
           (std::islower(static_cast<unsigned char>(text[end])) || text[end] == '_'))
      ++end;
    if (end < text.size() && text[end] == '}' && end > at + 1) {
      visit(text.substr(at + 1, end - at - 1), at, end);
      at = end + 1;
    } else {
      ++at;
    }
  }
}

}  // namespace

const std::vector<std::string>& system_placeholders() {
  static const std::vector<std::string> names = {"dataset",    "calibration",  "orbslam_settings",
                                                 "intrinsics", "depth_factor", "trajectory",
                                                 "keypoints",  "timestamps",   "work",
                                                 "system_dir", "depot"};
  return names;
}

const char* trajectory_format_name(TrajectoryFormat format) {
  switch (format) {
    case TrajectoryFormat::kTum:
      return "tum";
    case TrajectoryFormat::kKitti:
      return "kitti";
    case TrajectoryFormat::kEuroc:
      return "euroc";
  }
  return "tum";
}

bool is_system_mode(const std::string& mode) {
  return mode.rfind(kSystemModePrefix, 0) == 0;
}

std::string system_of_mode(const std::string& mode) {
  return is_system_mode(mode) ? mode.substr(std::string(kSystemModePrefix).size()) : "";
}

SystemSpec load_system_spec(const std::string& path) {
  const YAML::Node root = load_yaml_file(path, "system file");
  if (!root.IsMap()) fail(path, "a system file is a YAML map (command, trajectory_format, ...)");
  check_known_keys(root, {"description", "command", "trajectory_format", "time_limit_s", "env"},
                   path);
  SystemSpec spec;
  spec.path = path;
  spec.name = fs::path(path).stem().string();
  try {
    if (root["description"]) spec.description = root["description"].as<std::string>();
    const YAML::Node command = root["command"];
    if (!command) fail(path, "no command (a list: program and arguments)");
    if (!command.IsSequence() || command.size() == 0)
      fail(yaml_where(path, command), "command must be a non-empty list (program and arguments)");
    for (const auto& arg : command) spec.command.push_back(arg.as<std::string>());
    if (spec.command[0].empty()) fail(yaml_where(path, command), "command's program is empty");
    bool names_trajectory = false;
    for (const std::string& arg : spec.command)
      for_each_placeholder(arg, [&](const std::string& name, auto, auto) {
        const auto& known = system_placeholders();
        if (std::find(known.begin(), known.end(), name) == known.end()) {
          std::string list;
          for (const auto& k : known) list += (list.empty() ? "{" : ", {") + k + "}";
          fail(yaml_where(path, command),
               "unknown placeholder '{" + name + "}' (expected " + list + ")");
        }
        names_trajectory |= name == "trajectory";
        spec.writes_keypoints |= name == "keypoints";
        spec.writes_timestamps |= name == "timestamps";
      });
    if (!names_trajectory)
      fail(yaml_where(path, command), "the command never names {trajectory} (where to write it)");
    if (const YAML::Node format = root["trajectory_format"]) {
      const std::string f = format.as<std::string>();
      if (f == "tum")
        spec.trajectory_format = TrajectoryFormat::kTum;
      else if (f == "kitti")
        spec.trajectory_format = TrajectoryFormat::kKitti;
      else if (f == "euroc")
        spec.trajectory_format = TrajectoryFormat::kEuroc;
      else
        fail(yaml_where(path, format),
             "unknown trajectory_format '" + printable(f) + "' (expected tum, kitti, euroc)");
    }
    if (spec.writes_timestamps && spec.trajectory_format != TrajectoryFormat::kKitti)
      fail(yaml_where(path, command),
           "{timestamps} is for a KITTI trajectory (trajectory_format: kitti)");
    if (const YAML::Node limit = root["time_limit_s"]) {
      spec.time_limit_s = limit.as<double>();
      if (!(spec.time_limit_s > 0 && spec.time_limit_s <= 86400))
        fail(yaml_where(path, limit), "time_limit_s must be in (0, 86400] s");
    }
    if (const YAML::Node env = root["env"]) {
      if (!env.IsMap()) fail(yaml_where(path, env), "env must be a map NAME: value");
      for (const auto& kv : env) spec.env[kv.first.as<std::string>()] = kv.second.as<std::string>();
    }
  } catch (const YAML::Exception& e) {
    fail(path + ":" + std::to_string(e.mark.line + 1), "bad value: " + printable(e.msg));
  }
  return spec;
}

std::string find_system_file(const std::string& name) {
  if (name.empty()) fail("system", "no system named");
  const bool is_path = name.find('/') != std::string::npos ||
                       (name.size() > 5 && name.compare(name.size() - 5, 5, ".yaml") == 0);
  const std::string path = is_path ? name : project_file("scenes/systems/" + name + ".yaml");
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    fail(path, is_path ? "no such system file"
                       : "no such system file (system '" + name +
                             "' is looked for in scenes/systems/; give a path to use your own)");
  return path;
}

std::vector<std::string> expand_command(const SystemSpec& spec,
                                        const std::map<std::string, std::string>& values) {
  std::vector<std::string> argv;
  for (const std::string& arg : spec.command) {
    std::string out;
    size_t copied = 0;
    for_each_placeholder(arg, [&](const std::string& name, size_t at, size_t end) {
      const auto it = values.find(name);
      if (it == values.end()) fail(spec.path, "no value for placeholder {" + name + "}");
      out += arg.substr(copied, at - copied) + it->second;
      copied = end + 1;
    });
    argv.push_back(out + arg.substr(copied));
  }
  return argv;
}

}  // namespace depot::system
