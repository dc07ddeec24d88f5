#include "sim/scenario/scene_layout.h"

#include <yaml-cpp/yaml.h>

#include <fmt/format.h>

#include <cmath>
#include <set>
#include <sstream>

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
  if (!root.IsMap()) fail(path, "a scene layout is a map (hall, lights, objects)");
  const YamlFields top(root, path, "scene layout");
  top.allow_only({"hall", "lights", "objects", "finish", "routes"});
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
    // [x, y, z], or {position: [x, y, z], colour: [r, g, b]}.
    SceneLight light;
    if (l.IsMap()) {
      const YamlFields fields(l, path, "a light");
      fields.allow_only({"position", "colour"});
      if (!fields.has("position")) fail(yaml_where(path, l), "light needs 'position' [x, y, z]");
      light.position = fields.vec3("position", light.position);
      light.colour = fields.vec3("colour", light.colour);
      if (light.colour.minCoeff() < 0 || light.colour.maxCoeff() > 2)
        fail(yaml_where(path, l["colour"]), "light colour must lie in [0, 2]");
    } else {
      std::vector<double> v;
      try {
        v = l.as<std::vector<double>>();
      } catch (const YAML::Exception&) {
        v.clear();
      }
      if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
        fail(yaml_where(path, l), "light must be [x, y, z]");
      light.position = {v[0], v[1], v[2]};
    }
    layout.lights.push_back(light);
  }
  if (layout.lights.empty() || layout.lights.size() > 8) fail(path, "need 1 to 8 lights");
  if (const YAML::Node finish = root["finish"]) {
    const YamlFields fields(finish, path, "finish");
    fields.allow_only({"wall", "floor"});
    layout.wall_tint = fields.vec3("wall", layout.wall_tint);
    layout.floor_tint = fields.vec3("floor", layout.floor_tint);
    for (const Eigen::Vector3d* t : {&layout.wall_tint, &layout.floor_tint})
      if (t->minCoeff() < 0 || t->maxCoeff() > 2)
        fail(yaml_where(path, finish), "finish tints must lie in [0, 2]");
  }
  if (const YAML::Node routes = root["routes"]) {
    if (!routes.IsMap())
      fail(yaml_where(path, routes), "'routes' must be a map of name: [[x, y], ...]");
    for (const auto& kv : routes) {
      const std::string name = kv.first.as<std::string>();
      std::vector<Eigen::Vector2d> points;
      if (kv.second.IsSequence())
        for (const auto& p : kv.second) {
          std::vector<double> v;
          try {
            v = p.as<std::vector<double>>();
          } catch (const YAML::Exception&) {
            v.clear();
          }
          if (v.size() != 2 || !std::isfinite(v[0]) || !std::isfinite(v[1]))
            fail(yaml_where(path, p), "route '" + name + "': a point must be [x, y]");
          points.emplace_back(v[0], v[1]);
        }
      if (points.size() < 2)
        fail(yaml_where(path, kv.second), "route '" + name + "' needs at least two points [x, y]");
      layout.routes[name] = points;
    }
  }
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
    if (!layout.contains(o.position))
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

namespace {

std::string mm(double v) {
  return fmt::format("{:.3f}", std::abs(v) < 5e-4 ? 0.0 : v);
}

std::string list(std::initializer_list<double> values) {
  std::string out = "[";
  for (double v : values) out += (out.size() > 1 ? ", " : "") + mm(v);
  return out + "]";
}

std::string list3(const Eigen::Vector3d& v) {
  return list({v.x(), v.y(), v.z()});
}

}  // namespace

std::string scene_layout_yaml(const SceneLayout& l) {
  std::ostringstream y;
  y << "# " << l.path << "\n";
  y << "hall: {size: " << list({l.length, l.width}) << ", height: " << mm(l.height) << "}\n";
  y << "finish: {wall: " << list3(l.wall_tint) << ", floor: " << list3(l.floor_tint) << "}\n";
  y << "lights:\n";
  for (const SceneLight& light : l.lights)
    y << "  - {position: " << list3(light.position) << ", colour: " << list3(light.colour) << "}\n";
  y << "objects:\n";
  for (const SceneObject& o : l.objects) {
    y << "  - {type: " << o.type << ", name: " << o.name
      << ", position: " << list({o.position.x(), o.position.y()});
    if (o.yaw_deg != 0) y << ", yaw_deg: " << mm(o.yaw_deg);
    if (o.z != 0) y << ", z: " << mm(o.z);
    if (o.type == "rack" || o.type == "workbench" || o.type == "desk")
      y << ", length: " << mm(o.length);
    if (o.type == "rack") y << ", levels: " << o.levels;
    if (o.type == "crate_stack" || o.type == "sack_pile")
      y << ", count: [" << o.count.x() << ", " << o.count.y() << ", " << o.count.z() << "]";
    if (!o.model.empty()) y << ", model: " << o.model;
    y << "}\n";
  }
  if (!l.routes.empty()) {
    y << "routes:\n";
    for (const auto& [name, points] : l.routes) {
      y << "  " << name << ": [";
      for (size_t i = 0; i < points.size(); ++i)
        y << (i ? ", " : "") << list({points[i].x(), points[i].y()});
      y << "]\n";
    }
  }
  return y.str();
}

}  // namespace depot::sim
