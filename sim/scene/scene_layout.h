#pragma once
// The depot's static layout as data (scenes/depot.yaml): hall size, lights
// and the furniture placed in it.
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

struct SceneLayout {
  std::string path;
  double length = 20.0;  // x extent (m)
  double width = 12.0;   // y extent (m)
  double height = 4.5;
  std::vector<Eigen::Vector3d> lights;
  std::vector<SceneObject> objects;
};

// Throws depot::Error "<file>:<line>: <problem>" for bad layouts.
SceneLayout load_scene_layout(const std::string& path);

}  // namespace depot::sim
