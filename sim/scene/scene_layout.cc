#include "sim/scene/scene_layout.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

#include "common/error.h"
#include "common/yaml_fields.h"
#include "common/yaml_file.h"

namespace depot::sim {
namespace {

const std::set<std::string> kObjectTypes = {
    "rack", "crate_stack", "sack_pile", "pallet", "workbench", "desk", "barrel", "poster", "door"};

}  // namespace

SceneLayout load_scene_layout(const std::string& path) {
  YAML::Node root = load_yaml_file(path, "scene layout");
  SceneLayout layout;
  layout.path = path;
  YAML::Node hall = root["hall"];
  if (!hall) fail(path, "missing 'hall'");
  const YamlFields hall_fields(hall, path, "hall");
  auto size = hall_fields.get<std::vector<double>>("size", {20.0, 12.0});
  if (size.size() != 2 || !(size[0] > 2 && size[1] > 2))
    fail(yaml_where(path, hall), "hall size must be [length, width] > 2 m");
  layout.length = size[0];
  layout.width = size[1];
  layout.height = hall_fields.get<double>("height", 4.5);
  if (!(layout.height > 2.0 && layout.height < 20.0))
    fail(yaml_where(path, hall), "hall height out of range (2, 20) m");
  for (const auto& l : root["lights"]) {
    std::vector<double> v;
    try {
      v = l.as<std::vector<double>>();
    } catch (const YAML::Exception&) {
      v.clear();
    }
    if (v.size() != 3) fail(yaml_where(path, l), "light must be [x, y, z]");
    layout.lights.emplace_back(v[0], v[1], v[2]);
  }
  if (layout.lights.empty() || layout.lights.size() > 8) fail(path, "need 1 to 8 lights");
  int index = 0;
  for (const auto& n : root["objects"]) {
    const YamlFields fields(n, path, "a scene object");
    SceneObject o;
    o.type = fields.str("type");
    if (!kObjectTypes.count(o.type))
      fail(yaml_where(path, n), "unknown scene object type '" + o.type + "'");
    o.name = fields.get<std::string>("name", o.type + "_" + std::to_string(index++));
    auto p = fields.get<std::vector<double>>("position", {});
    if (p.size() != 2 || !std::isfinite(p[0]) || !std::isfinite(p[1]))
      fail(yaml_where(path, n), "object '" + o.name + "' needs position [x, y]");
    o.position = {p[0], p[1]};
    if (std::abs(p[0]) > layout.length / 2 || std::abs(p[1]) > layout.width / 2)
      fail(yaml_where(path, n), "object '" + o.name + "' is outside the hall");
    o.yaw_deg = fields.get<double>("yaw_deg", 0.0);
    o.z = fields.get<double>("z", 0.0);
    o.length = fields.get<double>("length", o.type == "desk" ? 1.4 : 2.4);
    o.levels = fields.get<int>("levels", 4);
    auto c = fields.get<std::vector<int>>("count", {1, 1, 1});
    if (c.size() != 3 || c[0] < 1 || c[1] < 1 || c[2] < 1 || c[0] * c[1] * c[2] > 200)
      fail(yaml_where(path, n), "count must be [nx, ny, nz] with 1..200 items");
    o.count = {c[0], c[1], c[2]};
    if (o.levels < 1 || o.levels > 8) fail(yaml_where(path, n), "rack levels must be 1..8");
    if (!(o.length > 0.2 && o.length < 20)) fail(yaml_where(path, n), "length out of range");
    o.model = fields.get<std::string>("model", "");
    if (!o.model.empty() && o.type != "desk")
      fail(yaml_where(path, n["model"]),
           "object '" + o.name + "': only desks take a catalogue 'model'");
    layout.objects.push_back(o);
  }
  return layout;
}

}  // namespace depot::sim
