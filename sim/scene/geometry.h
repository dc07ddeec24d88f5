#pragma once
// Plain descriptions of geoms before they become MJCF: what the scene and
// pushable builders produce and the MJCF writer consumes.
#include <string>
#include <vector>

#include "common/pose.h"
#include "sim/actors/actor.h"

namespace depot::sim {

// Collision groups (MuJoCo contype/conaffinity bits).
constexpr int kCollideWorld = 1;   // static depot, floor, pushables
constexpr int kCollidePusher = 2;  // a human's push plate touches pushables only

struct GeomDesc {
  Shape shape = Shape::kBox;
  Eigen::Vector3d size{0.1, 0.1, 0.1};  // MuJoCo size semantics
  Pose local = Pose::Identity();        // in the owning body's frame
  std::string material;
  int contype = kCollideWorld;
  int conaffinity = kCollideWorld;
  // MuJoCo takes the larger friction of two touching geoms: the floor is
  // slippery (0.05) so each pushable's own geoms set how it slides.
  double friction = 0.8;
  double density = 1000.0;
  bool visible = true;
  // Part of a prop's frame that a catalogue mesh draws when props are meshes
  // (props_style: mesh, sim/scene/mesh_props.h): the geom then stays for
  // physics but is hidden.
  bool replaced_by_mesh = false;
};

// One labelled instance's geometry, in the frame of its body.
struct InstanceGeometry {
  std::string name;
  std::string class_name;
  Pose pose = Pose::Identity();  // body pose in the world
  std::vector<GeomDesc> geoms;
};

GeomDesc box(const Eigen::Vector3d& half, const Eigen::Vector3d& at, const std::string& material,
             double yaw = 0.0);
GeomDesc cylinder(double radius, double half_height, const Eigen::Vector3d& at,
                  const std::string& material);

// Axis-aligned bounds of geoms in their body frame (conservative for round shapes).
Eigen::AlignedBox3d local_bounds(const std::vector<GeomDesc>& geoms);

}  // namespace depot::sim
