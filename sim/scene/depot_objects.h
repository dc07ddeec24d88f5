#pragma once
// Geometry of the depot's furniture and of the pushable objects, built from
// primitives. Each returns one or more labelled instances.
#include <cstdint>
#include <vector>

#include "sim/scene/geometry.h"
#include "sim/scenario/scene_layout.h"

namespace depot::sim {

// A static scene object (rack, crates, desk...): its instances (e.g. a rack
// and the goods on it, a desk and its monitor). Deterministic for a seed.
std::vector<InstanceGeometry> build_scene_object(const SceneObject& object, uint64_t seed);

// A free body that humans can push: "chair" or "cart", in its body frame
// (origin on the floor, x forward).
InstanceGeometry build_pushable(const std::string& type, const std::string& name, uint64_t seed);

// Height of a chair's seat above the floor.
constexpr double kChairSeatHeight = 0.46;

// A desk's top: its height above the floor and its depth (x; its length,
// along y, is the layout object's). The monitor stands on it at the +x edge;
// one sits at -x.
constexpr double kDeskTopHeight = 0.76;
constexpr double kDeskDepth = 0.8;

}  // namespace depot::sim
