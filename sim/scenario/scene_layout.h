#pragma once
// The depot's static layout as data: hall size, lights, the furniture placed
// in it and named routes through it. Read from a layout file (scenes/depot.yaml)
// or generated from a seed (sim/scenario/procedural_hall.h); the scene builder
// turns it into MuJoCo geometry.
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace depot::sim {

struct SceneObject {
  std::string type;  // rack, crate_stack, sack_pile, pallet, workbench, desk, barrel, poster, door
  std::string name;
  Eigen::Vector2d position{0, 0};
  double yaw_deg = 0.0;
  double z = 0.0;                  // base height (posters: centre height)
  double length = 2.4;             // racks, workbenches, desks (m)
  int levels = 4;                  // racks
  Eigen::Vector3i count{1, 1, 1};  // crate stacks / sack piles: nx, ny, nz
  // Desks: the asset catalogue entry (class desk) drawn when props are
  // meshes (props_style: mesh); "" = the catalogue's first desk.
  std::string model;
};

// A ceiling light: position and diffuse colour (MuJoCo's light diffuse).
struct SceneLight {
  Eigen::Vector3d position{0, 0, 4.3};
  Eigen::Vector3d colour{0.42, 0.42, 0.4};
};

struct SceneLayout {
  std::string path;      // the layout file, or "procedural hall (seed N)" for a generated one
  double length = 20.0;  // x extent (m)
  double width = 12.0;   // y extent (m)
  double height = 4.5;
  std::vector<SceneLight> lights;
  std::vector<SceneObject> objects;
  // Multipliers of the wall and floor materials' colour (their textures keep
  // their pattern): a painted wall, a lighter or darker floor.
  Eigen::Vector3d wall_tint{1, 1, 1};
  Eigen::Vector3d floor_tint{1, 1, 1};
  // Named ground paths through the layout (aisle centre lines, a patrol
  // loop), for `route:` in a scenario's motion and actors.
  std::map<std::string, std::vector<Eigen::Vector2d>> routes;

  // Whether a floor point lies in the hall, at least `margin` m from its walls.
  bool contains(const Eigen::Vector2d& p, double margin = 0.0) const {
    return std::abs(p.x()) <= length / 2 - margin && std::abs(p.y()) <= width / 2 - margin;
  }
};

// Throws depot::Error "<file>:<line>: <problem>" for bad layouts.
SceneLayout load_scene_layout(const std::string& path);

// The layout as a layout file load_scene_layout reads back to the same data
// (numbers to 1 mm / 0.001), e.g. a generated hall written beside a dataset.
std::string scene_layout_yaml(const SceneLayout& layout);

}  // namespace depot::sim
